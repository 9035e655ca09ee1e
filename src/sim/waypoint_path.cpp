#include "hex_slam/sim/waypoint_path.h"

#include <cmath>
#include <stdexcept>

namespace hex_slam {
namespace sim {

std::vector<Pose2> SampleWaypointPath(const std::vector<Eigen::Vector2d>& waypoints,
                                      double start_heading, const PathMotion& motion) {
  if (waypoints.empty()) return {};
  if (!(motion.linear_speed > 0 && motion.angular_speed > 0 && motion.rate > 0)) {
    throw std::invalid_argument("SampleWaypointPath: speeds and rate must be positive");
  }
  const double dt = 1.0 / motion.rate;
  std::vector<Pose2> poses;
  Pose2 pose(waypoints[0].x(), waypoints[0].y(), NormalizeAngle(start_heading));
  poses.push_back(pose);
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector2d target = waypoints[i];
    const Eigen::Vector2d delta = target - pose.translation();
    if (delta.norm() < 1e-9) continue;
    const double heading = std::atan2(delta.y(), delta.x());
    // Turn in place, then drive; every sample advances time by dt.
    double remaining_turn = NormalizeAngle(heading - pose.theta);
    const double max_turn = motion.angular_speed * dt;
    while (std::abs(remaining_turn) > 1e-12) {
      const double turn = std::max(-max_turn, std::min(max_turn, remaining_turn));
      pose.theta = NormalizeAngle(pose.theta + turn);
      remaining_turn -= turn;
      poses.push_back(pose);
    }
    pose.theta = heading;
    const double length = delta.norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(length / (motion.linear_speed * dt))));
    const Eigen::Vector2d start = pose.translation();
    for (int k = 1; k <= steps; ++k) {
      const Eigen::Vector2d p = start + delta * (static_cast<double>(k) / steps);
      pose.x = p.x();
      pose.y = p.y();
      poses.push_back(pose);
    }
  }
  return poses;
}

}  // namespace sim
}  // namespace hex_slam
