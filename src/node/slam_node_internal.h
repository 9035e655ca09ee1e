// Shared by slam_node.cpp (the scan side) and slam_node_map_output.cpp (the map thread).
#ifndef HEX_SLAM_NODE_SLAM_NODE_INTERNAL_H_
#define HEX_SLAM_NODE_SLAM_NODE_INTERNAL_H_

#include <chrono>

namespace hex_slam {
namespace node {
namespace internal {

// Throttled warnings repeat at most this often (s): a broken sensor at 40 Hz must not flood the
// log, yet stay visible.
constexpr double kWarnPeriod = 5.0;
inline double MillisecondsSince(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace internal
}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_SLAM_NODE_INTERNAL_H_
