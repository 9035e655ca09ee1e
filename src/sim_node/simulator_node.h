// hex_slam_sim: a 2D lidar simulator with stage_ros's interface, standing in for stage (which
// Debian does not package). A thin ROS adapter over the ROS-free simulation library: it loads a
// map_server world, drives the robot along a waypoint path (or by cmd_vel), and publishes
//   scan                   sensor_msgs/LaserScan in laser_frame
//   odom                   nav_msgs/Odometry, odom_frame -> base_frame, drifting like wheels
//   base_pose_ground_truth nav_msgs/Odometry, the true pose in ground_truth_frame
//   path_finished          std_msgs/Bool (latched), true once the path's last pose is reached
//   tf                     odom_frame -> base_frame (dynamic), base_frame -> laser_frame (static)
//   /clock                 when /use_sim_time is true
//
// Time: with /use_sim_time the node is the clock: each step advances simulated time by 1/rate
// and sleeps 1/(rate·real_time_factor) of wall time, so tests can run faster than real time
// and every subscriber sees exactly one scan per step. With lockstep_topics a step also waits
// until each listed pose topic has answered its scan, so a loaded machine slows the simulation
// down instead of making the nodes under test drop scans. Without sim time, messages carry
// wall time and the loop runs at `rate` Hz.
#ifndef HEX_SLAM_SRC_SIM_NODE_SIMULATOR_NODE_H_
#define HEX_SLAM_SRC_SIM_NODE_SIMULATOR_NODE_H_

#include <memory>
#include <random>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "hex_slam/sim/image_world.h"
#include "hex_slam/sim/odometry_model.h"
#include "hex_slam/sim/simulated_robot.h"
#include "hex_slam/sim/simulator_options.h"

namespace hex_slam {

class SimulatorNode {
 public:
  // Reads the private parameters; throws std::runtime_error naming every bad or unknown key, or
  // the world or path file that failed to load.
  SimulatorNode(ros::NodeHandle node, ros::NodeHandle private_node);

  // Steps until shutdown.
  void Run();

 private:
  // One step: the robot moves (unless still waiting at the start), then everything is published.
  void Step(const ros::Time& stamp, bool move);
  void OnCommand(const geometry_msgs::Twist& twist);
  void PublishStaticLaser(const ros::Time& stamp);

  // A pose topic the simulation waits for.
  struct Lockstep {
    std::string topic;
    ros::Subscriber subscriber;
    ros::Time latest;  // the newest pose's stamp
    bool answered = false;  // has published at least once
    bool late = false;      // the robot does not wait for its first answer to start
  };
  // Subscribes the space-separated [package:]topic list `topics`.
  void SubscribeLockstep(const std::string& topics, bool late);
  void OnLockstepPose(const geometry_msgs::PoseStamped::ConstPtr& pose, Lockstep* topic);
  // Every topic has answered at least once: the nodes are up and receiving scans.
  bool LockstepReady() const;
  // Waits (wall time, spinning) until every answered topic has a pose stamped `stamp` or later.
  void WaitForLockstep(const ros::Time& stamp);

  sim::SimulatorOptions options_;
  bool sim_time_ = false;
  ros::Time now_;  // the current step's stamp

  sim::ImageWorld world_;
  std::unique_ptr<sim::SimulatedRobot> robot_;
  std::unique_ptr<sim::DriftingOdometry> odometry_;
  std::mt19937_64 rng_;
  bool announced_finish_ = false;
  std::vector<std::unique_ptr<Lockstep>> lockstep_;
  long lockstep_timeouts_ = 0;

  ros::NodeHandle node_;
  ros::Publisher scan_pub_, odom_pub_, truth_pub_, clock_pub_, finished_pub_;
  ros::Subscriber cmd_sub_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_SRC_SIM_NODE_SIMULATOR_NODE_H_
