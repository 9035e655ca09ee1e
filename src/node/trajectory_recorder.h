// The estimated trajectory the node publishes (nav_msgs/Path): a pose kept after each step of
// min_distance or min_angle, thinned to every other pose when it reaches max_poses, so an hour's
// drive stays a message of bounded size that still covers the whole run.
#ifndef HEX_SLAM_NODE_TRAJECTORY_RECORDER_H_
#define HEX_SLAM_NODE_TRAJECTORY_RECORDER_H_

#include <vector>

#include "hex_slam/io/trajectory_io.h"

namespace hex_slam {
namespace node {

class TrajectoryRecorder {
 public:
  TrajectoryRecorder(double min_distance, double min_angle, int max_poses);

  // Returns true if the pose was kept.
  bool Add(double stamp, const Pose2& pose);
  void Clear() { poses_.clear(); }
  const std::vector<io::StampedPose>& poses() const { return poses_; }

 private:
  double min_distance_;
  double min_angle_;
  std::size_t max_poses_;
  std::vector<io::StampedPose> poses_;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_TRAJECTORY_RECORDER_H_
