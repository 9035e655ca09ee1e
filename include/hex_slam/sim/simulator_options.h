// Everything the simulator node is configured with, ROS-free so its one ParameterTable serves
// rosparam and the tests alike (unknown keys are errors).
#ifndef HEX_SLAM_SIM_SIMULATOR_OPTIONS_H_
#define HEX_SLAM_SIM_SIMULATOR_OPTIONS_H_

#include <string>
#include <vector>

#include "hex_slam/parameter_table.h"
#include "hex_slam/pose2.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/odometry_model.h"
#include "hex_slam/sim/simulated_robot.h"
#include "hex_slam/sim/waypoint_path.h"

namespace hex_slam {
namespace sim {

struct SimulatorOptions {
  std::string world;  // map_server YAML of the world (required)
  std::string path;   // waypoint path file; empty: stand at the start pose until cmd_vel arrives
  Pose2 start;        // the robot's pose when there is no path

  double rate = 10.0;  // Hz: one scan, one odometry message, one tf update per step
  // Simulated time runs this many times faster than the wall clock (with use_sim_time).
  double real_time_factor = 1.0;
  int seed = 1;  // the lidar noise and the odometry drift are deterministic for a seed
  // Wall seconds the robot stands at its start (publishing) before it moves, so nodes started
  // beside the simulator see the drive from its first metre.
  double start_delay = 1.0;

  LidarModel lidar;      // beams, field_of_view, range_min, range_max, range_noise
  Pose2 laser_mount;     // the laser in the base frame (laser_x, laser_y, laser_yaw)
  PathMotion motion;     // linear_speed, angular_speed along the path (rate is the step rate)
  RobotOptions robot;    // robot_radius, cmd_vel_timeout
  OdometryNoise odometry;

  std::string base_frame = "base_link";
  std::string odom_frame = "odom";
  std::string laser_frame = "laser";
  std::string ground_truth_frame = "world";  // the frame of base_pose_ground_truth

  SimulatorOptions();

  // Empty when valid; otherwise one message per bad field, naming its parameter.
  std::vector<std::string> Validate() const;
};

// The table binding each parameter name to its field in `options`.
ParameterTable SimulatorParameterTable(SimulatorOptions* options);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_SIMULATOR_OPTIONS_H_
