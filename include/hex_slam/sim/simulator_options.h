// Everything the simulator node is configured with, ROS-free so its one ParameterTable serves
// rosparam and the tests alike (unknown keys are errors).
#ifndef HEX_SLAM_SIM_SIMULATOR_OPTIONS_H_
#define HEX_SLAM_SIM_SIMULATOR_OPTIONS_H_

#include <string>
#include <vector>

#include "hex_slam/common/parameter_table.h"
#include "hex_slam/geometry/pose2.h"
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
  // beside the simulator see the drive from its first metre. With lockstep topics: simulated
  // seconds it stands still once every one of them has answered.
  double start_delay = 1.0;
  // Lockstep (with use_sim_time): PoseStamped topics whose publishers must each answer a step's
  // scan (a pose stamped at or after it) before the next step, so the nodes under test see
  // every scan however loaded the machine is. Space-separated; "package:topic" waits only when
  // that ROS package is installed (an optional comparison such as hector_mapping). The robot
  // starts once every topic has answered.
  std::string lockstep_topics;
  // The same for nodes that start later (a second node started during the run): each is waited
  // for from its first answer on, and the robot does not wait for it to start.
  std::string lockstep_late_topics;
  // Wall seconds a step waits for an answer before it goes on without it (and says so).
  double lockstep_timeout = 10.0;

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
