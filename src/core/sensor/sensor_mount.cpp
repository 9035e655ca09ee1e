#include "hex_slam/sensor/sensor_mount.h"

#include <cmath>

namespace hex_slam {
namespace {

// A rotation this close to one about z alone (its z axis within ~1e-9 rad of the base's) is
// treated as level, so a level laser given as a 3D transform maps points exactly as its pose.
constexpr double kLevelTolerance = 1e-9;

}  // namespace

SensorMount::SensorMount(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position) {
  const bool level = std::abs(rotation(2, 0)) < kLevelTolerance &&
                     std::abs(rotation(2, 1)) < kLevelTolerance && rotation(2, 2) > 0.0;
  if (level) {
    planar_ = Pose2(position.x(), position.y(), std::atan2(rotation(1, 0), rotation(0, 0)));
    to_base_ = PointTransform(planar_);
    level_ = true;
    return;
  }
  level_ = false;
  linear_ = rotation.topLeftCorner<2, 2>();
  origin_ = position.head<2>();
  height_ = Eigen::Vector2d(rotation(2, 0), rotation(2, 1));
}

Pose2 SensorMount::PlanarPose() const {
  if (level_) return planar_;
  return Pose2(origin_.x(), origin_.y(), std::atan2(linear_(1, 0), linear_(0, 0)));
}

}  // namespace hex_slam
