// Trajectory against ground truth. ATE: the estimate is moved by the rigid SE(2) transform that
// best fits its positions onto the ground truth's in the least-squares sense (Umeyama's method
// without scale), then the position errors' RMSE is taken. RPE: the motions over a fixed time
// step compared pose pair by pose pair, which needs no alignment (Sturm et al., TUM RGB-D).
#ifndef HEX_SLAM_LOGS_EVALUATION_TRAJECTORY_ERROR_H_
#define HEX_SLAM_LOGS_EVALUATION_TRAJECTORY_ERROR_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/logs/evaluation/sample_statistics.h"
#include "hex_slam/logs/evaluation/trajectory_lookup.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace logs {

// The T minimising sum |T * from[i] - to[i]|². Identity for fewer than two points; a pure
// translation when the points do not fix the rotation (all coincide).
Pose2 AlignPoints(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to);

struct TrajectoryErrorOptions {
  LookupOptions lookup;   // how ground-truth poses are found at the estimate's stamps
  double rpe_delta = 1.0;  // s between the two poses of each RPE pair
};

struct TrajectoryErrorReport {
  int poses = 0;    // estimate poses given
  int matched = 0;  // with a ground-truth pose
  Pose2 alignment;  // applied to the estimate
  SampleStatistics ate_translation;  // m, after alignment
  SampleStatistics ate_rotation;     // deg, after alignment
  SampleStatistics rpe_translation;  // m per rpe_delta
  SampleStatistics rpe_rotation;     // deg per rpe_delta
};

TrajectoryErrorReport EvaluateTrajectory(const std::vector<io::StampedPose>& estimate,
                                         const std::vector<io::StampedPose>& ground_truth,
                                         const TrajectoryErrorOptions& options);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_EVALUATION_TRAJECTORY_ERROR_H_
