#include "trajectory_recorder.h"

#include <algorithm>
#include <cmath>

namespace hex_slam {
namespace node {

TrajectoryRecorder::TrajectoryRecorder(double min_distance, double min_angle, int max_poses)
    : min_distance_(min_distance),
      min_angle_(min_angle),
      max_poses_(static_cast<std::size_t>(std::max(2, max_poses))) {}

bool TrajectoryRecorder::Add(double stamp, const Pose2& pose) {
  if (!poses_.empty()) {
    const Pose2 step = RelativePose(poses_.back().pose, pose);
    if (step.translation().norm() < min_distance_ && std::abs(step.theta) < min_angle_) {
      return false;
    }
  }
  if (poses_.size() >= max_poses_) {
    // Keep the even-indexed poses, the first one included: the shape survives, the size halves.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < poses_.size(); i += 2) poses_[kept++] = poses_[i];
    poses_.resize(kept);
  }
  poses_.push_back({stamp, pose});
  return true;
}

}  // namespace node
}  // namespace hex_slam
