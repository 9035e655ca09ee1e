// A rigid 2D pose (x, y, theta) and the few operations SLAM needs on it.
#ifndef HEX_SLAM_GEOMETRY_POSE2_H_
#define HEX_SLAM_GEOMETRY_POSE2_H_

#include <Eigen/Core>

namespace hex_slam {

// Wraps an angle to (-pi, pi].
double NormalizeAngle(double angle);

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Pose2() = default;
  Pose2(double x_in, double y_in, double theta_in) : x(x_in), y(y_in), theta(theta_in) {}

  Eigen::Vector2d translation() const { return {x, y}; }
  // Maps a point given in this pose's frame into the parent frame.
  Eigen::Vector2d operator*(const Eigen::Vector2d& point) const;
  // Composition: (this * other) applies `other` first, as for transforms.
  Pose2 operator*(const Pose2& other) const;
  Pose2 inverse() const;
};

// A pose applied to many points: its cosine and sine taken once instead of per point, bit for
// bit what Pose2::operator* gives (which is this).
class PointTransform {
 public:
  explicit PointTransform(const Pose2& pose);
  Eigen::Vector2d operator()(const Eigen::Vector2d& point) const {
    return {x_ + c_ * point.x() - s_ * point.y(), y_ + s_ * point.x() + c_ * point.y()};
  }

 private:
  double x_, y_, c_, s_;
};

// The motion from `from` to `to`, expressed in the `from` frame: from * delta == to.
Pose2 RelativePose(const Pose2& from, const Pose2& to);

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_POSE2_H_
