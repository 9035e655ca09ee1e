// The robot of the simulator node: it drives a pre-sampled waypoint path, one pose per step,
// until the first velocity command arrives; from then on it follows cmd_vel like stage's
// position model (a unicycle; it stops when commands stop coming and stalls instead of driving
// into a wall).
#ifndef HEX_SLAM_SIM_SIMULATED_ROBOT_H_
#define HEX_SLAM_SIM_SIMULATED_ROBOT_H_

#include <vector>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/world.h"

namespace hex_slam {
namespace sim {

struct RobotOptions {
  double radius = 0.15;  // m; a command that drives towards a wall closer than this stalls
  double cmd_vel_timeout = 0.5;  // s without a command and the robot stops
};

class SimulatedRobot {
 public:
  // `path`: poses one step apart (SampleWaypointPath at the step rate); empty means the robot
  // stands at `start` until commanded. `world` must outlive the robot.
  SimulatedRobot(const World& world, std::vector<Pose2> path, const Pose2& start,
                 const RobotOptions& options);

  // A velocity command (m/s forward, rad/s counter-clockwise) received at time `now`.
  void CommandVelocity(double linear, double angular, double now);
  // Advances the robot by one step of `dt` seconds ending at `now`; returns the new pose.
  const Pose2& Step(double now, double dt);

  const Pose2& pose() const { return pose_; }
  // The velocity of the last step: the executed command, or the path's speed.
  double linear_velocity() const { return linear_; }
  double angular_velocity() const { return angular_; }
  bool following_path() const { return !commanded_ && next_ < path_.size(); }
  bool path_finished() const { return !path_.empty() && next_ >= path_.size(); }
  bool stalled() const { return stalled_; }

 private:
  bool Collides(const Pose2& from, const Pose2& to) const;

  const World& world_;
  std::vector<Pose2> path_;
  std::size_t next_ = 1;  // path_[0] is the start pose
  RobotOptions options_;
  Pose2 pose_;
  bool commanded_ = false;
  double command_linear_ = 0.0, command_angular_ = 0.0, command_time_ = 0.0;
  double linear_ = 0.0, angular_ = 0.0;
  bool stalled_ = false;
};

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_SIMULATED_ROBOT_H_
