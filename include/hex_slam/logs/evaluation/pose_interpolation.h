// Poses between two stamped poses: translation linear, heading along the shorter arc.
#ifndef HEX_SLAM_LOGS_EVALUATION_POSE_INTERPOLATION_H_
#define HEX_SLAM_LOGS_EVALUATION_POSE_INTERPOLATION_H_

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace logs {

// fraction 0 gives `a`, 1 gives `b`.
inline Pose2 InterpolatePose(const Pose2& a, const Pose2& b, double fraction) {
  return Pose2(a.x + fraction * (b.x - a.x), a.y + fraction * (b.y - a.y),
               NormalizeAngle(a.theta + fraction * NormalizeAngle(b.theta - a.theta)));
}

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_EVALUATION_POSE_INTERPOLATION_H_
