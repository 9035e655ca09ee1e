// Where the laser sits on the base, as the planar core uses it. A level laser is a planar pose. A
// tilted one (a pitching or rolling mount, an IMU-stabilised frame, a laser upside down) sees its
// beams' plane at an angle to the base's x-y plane: its points project onto that plane through
// the top-left 2x2 block of its 3D rotation, and their height above the laser is the rotation's
// third row times the beam point. hector_mapping keeps the points whose height lies within
// (laser_z_min_value, laser_z_max_value); so does the core.
#ifndef HEX_SLAM_SENSOR_SENSOR_MOUNT_H_
#define HEX_SLAM_SENSOR_SENSOR_MOUNT_H_

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {

class SensorMount {
 public:
  // The laser at the base's origin, level.
  SensorMount() = default;
  // A level laser at `pose` on the base: points map exactly as `pose * point`.
  explicit SensorMount(const Pose2& pose) : planar_(pose), to_base_(pose), level_(true) {}
  // Any mount: the laser's rotation and position in the base frame.
  SensorMount(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position);

  // A beam point (laser frame, its scan plane) in the base's plane.
  Eigen::Vector2d ToBase(const Eigen::Vector2d& point) const {
    return level_ ? to_base_(point) : linear_ * point + origin_;
  }
  // How far above the laser (along the base's z) the beam point lies; 0 for a level laser.
  double HeightOf(const Eigen::Vector2d& point) const {
    return level_ ? 0.0 : height_.dot(point);
  }
  // Where the beams start, in the base's plane.
  Eigen::Vector2d origin() const { return level_ ? planar_.translation() : origin_; }
  // Where the laser stands on the base's plane and which way its x axis points there.
  Pose2 PlanarPose() const;
  bool level() const { return level_; }

 private:
  Pose2 planar_;
  PointTransform to_base_{Pose2()};  // planar_'s, its cosine and sine taken once
  bool level_ = true;
  Eigen::Matrix2d linear_ = Eigen::Matrix2d::Identity();
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d height_ = Eigen::Vector2d::Zero();
};

}  // namespace hex_slam

#endif  // HEX_SLAM_SENSOR_SENSOR_MOUNT_H_
