// Logs whose stamps go backwards. In the Intel log 265 scans are stamped up to 0.9 s late while
// the odometry in the same lines advances smoothly: the recording order is right and the odd
// stamp is wrong. The processor needs non-decreasing time, so a stamp later than its successor's
// is lowered to it ("delivered late"); every other stamp is kept exactly, so trajectories still
// match reference data keyed by the log's stamps.
#ifndef HEX_SLAM_LOGS_STAMP_ORDER_H_
#define HEX_SLAM_LOGS_STAMP_ORDER_H_

#include <vector>

namespace hex_slam {
namespace logs {

// Non-decreasing stamps: out[i] = min(stamps[i], out[i + 1]). Returns how many changed.
int MakeStampsNonDecreasing(const std::vector<double>& stamps, std::vector<double>* out);

// The same, keeping each lowered stamp `min_step` below its successor, for consumers that
// refuse repeated stamps (tf2). `out` may be `&stamps`.
int MakeStampsIncreasing(const std::vector<double>& stamps, double min_step,
                         std::vector<double>* out);

// How many times stamps[i] < stamps[i - 1].
int CountBackwardSteps(const std::vector<double>& stamps);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_STAMP_ORDER_H_
