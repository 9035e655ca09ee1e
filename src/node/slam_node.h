// hex_slam_node: hector_mapping's topics, services, tf and parameters around hex_slam::Slam.
//
// Threads: scans, commands, initial poses, reset_map and pause_mapping run on the global callback
// queue (ros::spin in main). Map output — the map and map_metadata timer, the hex_map marker,
// the trajectory, dynamic_map and save_map — runs on a queue of its own with its own thread, so a
// scan never waits for rasterising or publishing. One mutex guards the Slam and what changes with
// it; the map thread holds it only to copy a snapshot of the finest level.
#ifndef HEX_SLAM_NODE_SLAM_NODE_H_
#define HEX_SLAM_NODE_SLAM_NODE_H_

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/GetMap.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include "hex_slam/slam.h"
#include "map_snapshot.h"
#include "node_options.h"
#include "scan_clock.h"
#include "tf_helper.h"
#include "timing_stats.h"
#include "trajectory_recorder.h"

namespace hex_slam {
namespace node {

// Scans the node did not match, by reason (each also logged, throttled).
struct DropCounters {
  long no_laser_transform = 0;  // tf could not place the scan's frame on the base
  long invalid = 0;             // malformed: NaN limits, bad increment, size mismatch, ...
  long late = 0;                // stamped slightly before the previous scan
  long paused = 0;              // pause_mapping was on
  long errors = 0;              // the core threw (out of memory, ...)
  long no_odometry = 0;         // matched, but without the odometry prior
  long time_jump_resets = 0;    // the map was reset because the stamps jumped back
};

class SlamNode {
 public:
  // `config` must be valid (NodeConfig::Validate() empty).
  SlamNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, const NodeConfig& config);
  ~SlamNode();

  // For the end-of-run summary; call after spinning stopped.
  const TimingStats& timing() const { return timing_; }
  const DropCounters& drops() const { return drops_; }

 private:
  // Global queue.
  void OnScan(const sensor_msgs::LaserScan::ConstPtr& msg);
  void OnSysCommand(const std_msgs::String::ConstPtr& msg);
  void OnInitialPose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg);
  bool OnResetMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool OnPauseMapping(std_srvs::SetBool::Request& request, std_srvs::SetBool::Response& response);
  // Map queue.
  void OnMapTimer(const ros::TimerEvent& event);
  void OnHexMapTimer(const ros::TimerEvent& event);
  bool OnDynamicMap(nav_msgs::GetMap::Request& request, nav_msgs::GetMap::Response& response);
  bool OnSaveMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  // Scan steps; false means the scan was dropped (and counted).
  bool LaserMountOf(const sensor_msgs::LaserScan& msg, LaserMount* mount);
  // Under mutex_: what the stamp means (drop, reset, go on).
  bool AdmitStamp(const LaserScan& scan);
  void PublishPose(const ScanReport& report, const ros::Time& stamp);
  void PublishTransforms(const Pose2& pose, const std::optional<Pose2>& odom_to_base,
                         const ros::Time& stamp);
  // Keeps tf alive while scans are dropped or paused: the last map->odom, newly stamped.
  void RepublishTransforms(const ros::Time& stamp);
  void ResetLocked(const Pose2& pose);  // under mutex_

  // Map thread: brings the snapshot and the occupancy grid up to the map's current version.
  void RefreshMap();

  NodeOptions options_;
  bool has_odometry_frame_;  // odom_frame != base_frame

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  ros::NodeHandle map_nh_;  // serviced by map_spinner_
  ros::CallbackQueue map_queue_;
  ros::AsyncSpinner map_spinner_;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;

  // Guards the Slam and what changes with it.
  std::mutex mutex_;
  Slam slam_;
  ScanClock scan_clock_;
  TrajectoryRecorder trajectory_;
  std::uint64_t map_generation_ = 0;  // bumped by every map change and reset

  // Global-queue state (one thread, no lock).
  TfHelper tf_helper_;
  bool paused_ = false;
  std::optional<geometry_msgs::TransformStamped> last_map_transform_;  // map->odom or map->base
  ros::Time last_tf_stamp_;  // tf listeners reject a stamp twice or going back
  TimingStats timing_;
  DropCounters drops_;

  // Map-thread state (one thread, no lock).
  std::optional<MapSnapshot> snapshot_;
  nav_msgs::OccupancyGrid map_msg_;
  std::uint64_t map_msg_generation_ = 0;
  bool have_map_msg_ = false;
  std::uint64_t marker_generation_ = 0;
  bool have_marker_ = false;

  ros::Subscriber scan_sub_, command_sub_, initial_pose_sub_;
  ros::Publisher pose_pub_, pose_update_pub_, odometry_pub_, map_pub_, map_metadata_pub_,
      hex_map_pub_, trajectory_pub_;
  ros::ServiceServer reset_service_, pause_service_, dynamic_map_service_, save_map_service_;
  ros::Timer map_timer_, hex_map_timer_;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_SLAM_NODE_H_
