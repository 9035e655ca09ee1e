#include "hex_slam/geometry/pose2.h"

#include <cmath>

namespace hex_slam {

double NormalizeAngle(double angle) {
  angle = std::remainder(angle, 2.0 * M_PI);
  return angle <= -M_PI ? angle + 2.0 * M_PI : angle;
}

PointTransform::PointTransform(const Pose2& pose)
    : x_(pose.x), y_(pose.y), c_(std::cos(pose.theta)), s_(std::sin(pose.theta)) {}

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& point) const {
  return PointTransform(*this)(point);
}

Pose2 Pose2::operator*(const Pose2& other) const {
  const Eigen::Vector2d t = (*this) * other.translation();
  return {t.x(), t.y(), NormalizeAngle(theta + other.theta)};
}

Pose2 Pose2::inverse() const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {-c * x - s * y, s * x - c * y, NormalizeAngle(-theta)};
}

Pose2 RelativePose(const Pose2& from, const Pose2& to) { return from.inverse() * to; }

}  // namespace hex_slam
