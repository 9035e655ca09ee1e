#include "hex_slam/sim/odometry_model.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hex_slam {
namespace sim {
namespace {

// A scale error beyond this is not odometry any more.
constexpr double kMaxScaleError = 0.5;

}  // namespace

OdometryNoise OdometryNoise::Typical() {
  OdometryNoise n;
  n.translation_stddev = 0.01;
  n.rotation_stddev = 0.01;
  n.rotation_stddev_per_distance = 0.5 * M_PI / 180.0;
  n.translation_scale_error = 0.01;
  n.rotation_scale_error = 0.01;
  return n;
}

std::vector<std::string> OdometryNoise::Validate() const {
  std::vector<std::string> errors;
  const auto stddev = [&](const char* name, double v) {
    if (!(std::isfinite(v) && v >= 0.0)) errors.push_back(std::string(name) + " must be >= 0");
  };
  const auto scale = [&](const char* name, double v) {
    if (!(std::isfinite(v) && std::abs(v) <= kMaxScaleError)) {
      std::ostringstream s;
      s << name << " must lie in [-" << kMaxScaleError << ", " << kMaxScaleError << "]";
      errors.push_back(s.str());
    }
  };
  stddev("odom_translation_stddev", translation_stddev);
  stddev("odom_rotation_stddev", rotation_stddev);
  stddev("odom_rotation_stddev_per_distance", rotation_stddev_per_distance);
  scale("odom_translation_scale_error", translation_scale_error);
  scale("odom_rotation_scale_error", rotation_scale_error);
  return errors;
}

DriftingOdometry::DriftingOdometry(const OdometryNoise& noise, std::uint64_t seed,
                                   const Pose2& start)
    : noise_(noise), rng_(seed), unit_(0.0, 1.0), pose_(start) {
  const std::vector<std::string> errors = noise.Validate();
  if (!errors.empty()) throw std::invalid_argument("DriftingOdometry: " + errors.front());
}

const Pose2& DriftingOdometry::Update(const Pose2& true_pose) {
  if (!started_) {
    started_ = true;
    last_true_ = true_pose;
    return pose_;
  }
  const Pose2 motion = RelativePose(last_true_, true_pose);
  last_true_ = true_pose;
  const double distance = motion.translation().norm();
  const double turn = std::abs(motion.theta);
  // Draw every variate every step, so one noise source set to zero does not shift the others'
  // random sequence.
  const double n_trans = unit_(rng_), n_rot = unit_(rng_), n_rot_dist = unit_(rng_);
  double along = noise_.translation_scale_error * distance +
                 noise_.translation_stddev * std::sqrt(distance) * n_trans;
  const double dtheta = motion.theta * (1.0 + noise_.rotation_scale_error) +
                        noise_.rotation_stddev * std::sqrt(turn) * n_rot +
                        noise_.rotation_stddev_per_distance * std::sqrt(distance) * n_rot_dist;
  Eigen::Vector2d translation = motion.translation();
  if (distance > 0.0) translation += translation / distance * along;
  pose_ = pose_ * Pose2(translation.x(), translation.y(), dtheta);
  pose_.theta = NormalizeAngle(pose_.theta);
  return pose_;
}

}  // namespace sim
}  // namespace hex_slam
