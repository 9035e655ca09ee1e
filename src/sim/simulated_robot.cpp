#include "hex_slam/sim/simulated_robot.h"

#include <cmath>

namespace hex_slam {
namespace sim {
namespace {

// Turns smaller than this per step are integrated as straight lines.
constexpr double kStraightTurn = 1e-9;

}  // namespace

SimulatedRobot::SimulatedRobot(const World& world, std::vector<Pose2> path, const Pose2& start,
                               const RobotOptions& options)
    : world_(world),
      path_(std::move(path)),
      options_(options),
      pose_(path_.empty() ? start : path_.front()) {}

void SimulatedRobot::CommandVelocity(double linear, double angular, double now) {
  if (!std::isfinite(linear) || !std::isfinite(angular)) return;
  commanded_ = true;
  command_linear_ = linear;
  command_angular_ = angular;
  command_time_ = now;
}

bool SimulatedRobot::Collides(const Pose2& from, const Pose2& to) const {
  const Eigen::Vector2d move = to.translation() - from.translation();
  const double distance = move.norm();
  // A wall ahead within the step plus the radius; along the whole step, so a thin wall is not
  // jumped over. Moving away from or along a close wall stays allowed.
  return distance > 0.0 &&
         std::isfinite(world_.CastRay(from.translation(), std::atan2(move.y(), move.x()),
                                      distance + options_.radius));
}

const Pose2& SimulatedRobot::Step(double now, double dt) {
  stalled_ = false;
  if (!commanded_) {
    const Pose2 before = pose_;
    if (next_ < path_.size()) pose_ = path_[next_++];
    const Pose2 moved = RelativePose(before, pose_);
    const double distance = moved.translation().norm();
    linear_ = dt > 0.0 ? (moved.x < 0.0 ? -distance : distance) / dt : 0.0;
    angular_ = dt > 0.0 ? moved.theta / dt : 0.0;
    return pose_;
  }
  const bool fresh = now - command_time_ <= options_.cmd_vel_timeout;
  const double v = fresh ? command_linear_ : 0.0;
  const double w = fresh ? command_angular_ : 0.0;
  // Exact unicycle motion over the step: an arc of radius v/w.
  const double turn = w * dt;
  Pose2 delta;
  if (std::abs(turn) < kStraightTurn) {
    delta = Pose2(v * dt, 0.0, turn);
  } else {
    const double r = v / w;
    delta = Pose2(r * std::sin(turn), r * (1.0 - std::cos(turn)), turn);
  }
  Pose2 next = pose_ * delta;
  next.theta = NormalizeAngle(next.theta);
  if (delta.translation().norm() > 0.0 && Collides(pose_, next)) {
    next = Pose2(pose_.x, pose_.y, next.theta);  // stage stalls: turning is still allowed
    stalled_ = true;
  }
  pose_ = next;
  linear_ = stalled_ ? 0.0 : v;
  angular_ = w;
  return pose_;
}

}  // namespace sim
}  // namespace hex_slam
