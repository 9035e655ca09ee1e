#include "hex_slam/sim/simulator_options.h"

#include <cmath>

namespace hex_slam {
namespace sim {

SimulatorOptions::SimulatorOptions() {
  // An RPLidar-like 360° scanner at 10 Hz with 1 cm noise, odometry of a typical small robot.
  lidar.beams = 360;
  lidar.field_of_view = 2.0 * M_PI;
  lidar.range_min = 0.05;
  lidar.range_max = 8.0;
  lidar.range_noise_stddev = 0.01;
  odometry = OdometryNoise::Typical();
}

std::vector<std::string> SimulatorOptions::Validate() const {
  std::vector<std::string> errors = odometry.Validate();
  auto require = [&errors](bool ok, const std::string& message) {
    if (!ok) errors.push_back(message);
  };
  require(!world.empty(), "world (a map_server YAML) is required");
  require(std::isfinite(start.x) && std::isfinite(start.y) && std::isfinite(start.theta),
          "start_x, start_y, start_yaw must be finite");
  require(rate > 0.0 && rate <= 1000.0, "rate must lie in (0, 1000] Hz");
  require(real_time_factor > 0.0, "real_time_factor must be > 0");
  require(seed >= 0, "seed must be >= 0");
  require(start_delay >= 0.0 && std::isfinite(start_delay), "start_delay must be >= 0");
  require(lockstep_timeout > 0.0 && std::isfinite(lockstep_timeout),
          "lockstep_timeout must be > 0");
  require(lidar.beams >= 3, "beams must be >= 3");
  require(lidar.field_of_view > 0.0 && lidar.field_of_view <= 2.0 * M_PI,
          "field_of_view must lie in (0, 2 pi]");
  require(lidar.range_min >= 0.0, "range_min must be >= 0");
  require(lidar.range_max > lidar.range_min, "range_max must exceed range_min");
  require(lidar.range_noise_stddev >= 0.0, "range_noise must be >= 0");
  require(std::isfinite(laser_mount.x) && std::isfinite(laser_mount.y) &&
              std::isfinite(laser_mount.theta),
          "laser_x, laser_y, laser_yaw must be finite");
  require(motion.linear_speed > 0.0, "linear_speed must be > 0");
  require(motion.angular_speed > 0.0, "angular_speed must be > 0");
  require(robot.radius >= 0.0, "robot_radius must be >= 0");
  require(robot.cmd_vel_timeout > 0.0, "cmd_vel_timeout must be > 0");
  for (const std::string* frame : {&base_frame, &odom_frame, &laser_frame, &ground_truth_frame}) {
    require(!frame->empty(), "frame names must not be empty");
  }
  return errors;
}

ParameterTable SimulatorParameterTable(SimulatorOptions* o) {
  ParameterTable t;
  t.Add("world", &o->world, "map_server YAML of the world (image + resolution + origin)");
  t.Add("path", &o->path, "waypoint path file; empty: stand at start_* until cmd_vel");
  t.Add("start_x", &o->start.x, "start pose without a path, m");
  t.Add("start_y", &o->start.y, "start pose without a path, m");
  t.Add("start_yaw", &o->start.theta, "start heading without a path, rad");
  t.Add("rate", &o->rate, "scans (and odometry, tf) per second");
  t.Add("real_time_factor", &o->real_time_factor, "sim time per wall time, with use_sim_time");
  t.Add("seed", &o->seed, "seed of the range noise and the odometry drift");
  t.Add("start_delay", &o->start_delay,
        "seconds standing at the start before moving (wall; simulated with lockstep_topics)");
  t.Add("lockstep_topics", &o->lockstep_topics,
        "PoseStamped topics ([package:]topic, space-separated) answering each scan before the "
        "next step");
  t.Add("lockstep_late_topics", &o->lockstep_late_topics,
        "lockstep topics of nodes started later: waited for from their first pose on");
  t.Add("lockstep_timeout", &o->lockstep_timeout,
        "wall seconds a step waits for the lockstep topics");
  t.Add("beams", &o->lidar.beams, "beams per scan");
  t.Add("field_of_view", &o->lidar.field_of_view, "scan width, rad, centred on the laser's x");
  t.Add("range_min", &o->lidar.range_min, "closer returns read -inf, m");
  t.Add("range_max", &o->lidar.range_max, "no return beyond this reads +inf, m");
  t.Add("range_noise", &o->lidar.range_noise_stddev, "Gaussian range noise, m (stddev)");
  t.Add("laser_x", &o->laser_mount.x, "laser position in the base frame, m");
  t.Add("laser_y", &o->laser_mount.y, "laser position in the base frame, m");
  t.Add("laser_yaw", &o->laser_mount.theta, "laser heading in the base frame, rad");
  t.Add("linear_speed", &o->motion.linear_speed, "speed along the path, m/s");
  t.Add("angular_speed", &o->motion.angular_speed, "turning speed at waypoints, rad/s");
  t.Add("robot_radius", &o->robot.radius, "commands driving closer to a wall stall, m");
  t.Add("cmd_vel_timeout", &o->robot.cmd_vel_timeout, "stop after this long without cmd_vel, s");
  t.Add("odom_translation_stddev", &o->odometry.translation_stddev,
        "odometry distance noise, m per sqrt(m) driven");
  t.Add("odom_rotation_stddev", &o->odometry.rotation_stddev,
        "odometry heading noise, rad per sqrt(rad) turned");
  t.Add("odom_rotation_stddev_per_distance", &o->odometry.rotation_stddev_per_distance,
        "odometry heading noise, rad per sqrt(m) driven");
  t.Add("odom_translation_scale_error", &o->odometry.translation_scale_error,
        "systematic odometry distance error, fraction");
  t.Add("odom_rotation_scale_error", &o->odometry.rotation_scale_error,
        "systematic odometry turn error, fraction");
  t.Add("base_frame", &o->base_frame, "the robot's frame");
  t.Add("odom_frame", &o->odom_frame, "the odometry frame (parent of base_frame)");
  t.Add("laser_frame", &o->laser_frame, "the scan's frame (child of base_frame)");
  t.Add("ground_truth_frame", &o->ground_truth_frame, "frame of base_pose_ground_truth");
  return t;
}

}  // namespace sim
}  // namespace hex_slam
