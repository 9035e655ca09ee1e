// The pose of a trajectory at a given time, for comparing it with reference data keyed by time.
// A pose stamped within `match_tolerance` of the query is taken as it is (reference data made from
// the same log shares its stamps exactly); otherwise the two poses around the query are
// interpolated, provided they are at most `max_gap` apart. Further from any pose, there is none:
// the comparison skips that time rather than invent a pose.
#ifndef HEX_SLAM_LOGS_EVALUATION_TRAJECTORY_LOOKUP_H_
#define HEX_SLAM_LOGS_EVALUATION_TRAJECTORY_LOOKUP_H_

#include <optional>
#include <vector>

#include "hex_slam/io/trajectory_io.h"

namespace hex_slam {
namespace logs {

struct LookupOptions {
  double match_tolerance = 1e-3;  // s: a TUM file keeps stamps to the microsecond
  // s: half the scan period of a 5 Hz log, so a trajectory with a pose per scan is only ever
  // read at its own stamps, while denser ones (10 Hz and up) interpolate. Interpolating across
  // longer gaps would hide a trajectory with holes.
  double max_gap = 0.1;
};

class TrajectoryLookup {
 public:
  // `poses` in any order; for equal stamps the first one wins.
  explicit TrajectoryLookup(std::vector<io::StampedPose> poses);

  std::optional<Pose2> At(double stamp, const LookupOptions& options) const;
  std::size_t size() const { return poses_.size(); }

 private:
  std::vector<io::StampedPose> poses_;  // sorted by stamp
};

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_EVALUATION_TRAJECTORY_LOOKUP_H_
