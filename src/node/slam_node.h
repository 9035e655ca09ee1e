// hex_slam_node: hector_mapping's topics, services, tf and parameters around hex_slam::Slam.
//
// Threads:
//   - the scan subscriber (a callback queue and spinner of its own, shared with tf2's listener)
//     only appends each scan to the ScanQueue, so ROS never drops a scan silently;
//   - the SLAM thread takes scans from that queue: tf lookups, the core's ProcessScan, the pose
//     and tf it publishes;
//   - the global callback queue (ros::spin in main): commands, initial poses, reset_map,
//     restart_mapping_with_new_pose, pause_mapping;
//   - the map thread (a queue of its own): the map and map_metadata, the hex_map marker, the
//     trajectory, diagnostics, dynamic_map, save_map, plan_path.
// One mutex guards the Slam and what changes with it. The map thread holds it only to bring its
// snapshot up to date with the cells changed since its last refresh, never to copy a whole map.
#ifndef HEX_SLAM_NODE_SLAM_NODE_H_
#define HEX_SLAM_NODE_SLAM_NODE_H_

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <hex_slam/ResetMapping.h>
#include <nav_msgs/GetMap.h>
#include <nav_msgs/GetPlan.h>
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

#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/mapping/slam.h"
#include "map_output/map_snapshot.h"
#include "map_output/redrawn_map.h"
#include "node_diagnostics.h"
#include "node_options.h"
#include "ros_input/scan_clock.h"
#include "ros_input/scan_queue.h"
#include "ros_input/tf_helper.h"
#include "trajectory_recorder.h"

namespace hex_slam {
namespace node {

class SlamNode {
 public:
  // `config` must be valid (NodeConfig::Validate() empty).
  SlamNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, const NodeConfig& config);
  ~SlamNode();

  // A copy of the counters, e.g. for the end-of-run summary.
  ScanStats stats();

  // Loads options' map_file (if set) into the Slam, and keeps it to reload on every reset.
  // Returns an empty string or the error (the node should not start then).
  std::string LoadMapFile();

  // After LoadMapFile: publishes the map, offers the services and starts taking scans.
  void Start();

 private:
  using ScanPtr = sensor_msgs::LaserScan::ConstPtr;

  // Scan subscriber thread.
  void OnScanReceived(const ScanPtr& msg);
  // SLAM thread.
  void ScanLoop();
  void MapLoop();
  void ProcessScanMessage(const sensor_msgs::LaserScan& msg,
                          std::chrono::steady_clock::time_point received);
  // Global queue.
  void OnSysCommand(const std_msgs::String::ConstPtr& msg);
  void OnInitialPose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg);
  bool OnResetMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool OnRestartWithPose(hex_slam::ResetMapping::Request& request,
                         hex_slam::ResetMapping::Response& response);
  bool OnPauseMapping(std_srvs::SetBool::Request& request, std_srvs::SetBool::Response& response);
  // Map queue.
  void OnMapTimer(const ros::WallTimerEvent& event);
  void OnHexMapTimer(const ros::WallTimerEvent& event);
  bool OnDynamicMap(nav_msgs::GetMap::Request& request, nav_msgs::GetMap::Response& response);
  bool OnSaveMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool OnPlanPath(nav_msgs::GetPlan::Request& request, nav_msgs::GetPlan::Response& response);
  // rviz's "2D Nav Goal": a plan from the robot's pose, published on planned_path.
  void OnGoal(const geometry_msgs::PoseStamped::ConstPtr& goal);
  void PublishDiagnostics();

  // Counts one dropped scan under `counter`; returns the new count for the log message.
  long CountDrop(long DropCounters::*counter);
  // The laser's mount on the base at the scan's stamp; false means the scan was dropped (and
  // counted).
  bool MountAt(const sensor_msgs::LaserScan& msg, SensorMount* mount);
  // odom->base at the scan's stamp (for the prior and for map->odom), if wanted and known.
  std::optional<Pose2> OdometryAt(const ros::Time& stamp);
  // Odometry at `stamp` without waiting, for tf once the scan is matched; none before any came.
  std::optional<Pose2> LateOdometryAt(const ros::Time& stamp) const;
  // tf map->base at the stamp, with use_tf_pose_start_estimate.
  std::optional<Pose2> StartEstimateAt(const ros::Time& stamp);
  // How long (wall s) the SLAM thread may wait for a transform at a scan's stamp: tf_timeout,
  // but never more than the time between scans, so waiting cannot make it fall behind.
  double TfWait() const;
  // Under mutex_: what the stamp means (drop, reset, go on).
  bool AdmitStamp(const LaserScan& scan);
  // While lost: poseupdate and scanmatch_odom with the unconstrained covariance, no slam_out_pose
  // (it has no covariance to say the pose is not known).
  void PublishPose(const ScanReport& report, const ros::Time& stamp);
  // Puts the scan ProcessScan deferred into the map, after its pose went out.
  void InsertDeferredScan(ScanReport* report);
  // A scan went into the map over `region` (world box): the map thread's snapshot is stale there.
  // Under mutex_.
  void NoteMapChanged(const Eigen::AlignedBox2d& region);
  // The tracking state into the counters; on a change, the log and the latched topic.
  // `times_lost`, `relocalizations`, `restarts`: the core's counts after this scan.
  void NoteTracking(const ScanReport& report, long times_lost, long relocalizations,
                    long restarts);
  void PublishTrackingState(TrackingState state);
  // map->odom for `pose`: from `odom_to_base`, else from odometry that came after the match
  // (LateOdometryAt), else the last correction; map->scanmatcher_frame if asked.
  void PublishTransforms(const Pose2& pose, const std::optional<Pose2>& odom_to_base,
                         const ros::Time& stamp);
  // Keeps tf alive while scans are dropped or paused: the last map->odom, newly stamped. With
  // `holding` (lost: the core holds the pose, or lets odometry carry it) map->base too.
  void RepublishTransforms(const ros::Time& stamp, bool holding = false);
  void ResetLocked(const Pose2& pose);  // under mutex_
  // Under mutex_, just before ProcessScan: makes the core start this scan's match at `target`
  // (the base's pose at the scan's stamp). The core adds the odometry's motion since its previous
  // scan to its pose, so that motion is taken out first.
  void StartScanAt(Pose2 target, const std::optional<Pose2>& prior);
  // Latched at start-up, as hector does: the map (empty, or map_file's) and its metadata.
  void PublishInitialMap();
  // Start's steps: the global queue's subscriptions and services; the map thread's.
  void AdvertiseCommands();
  void AdvertiseMapOutput();

  // Map thread: brings the snapshot up to the map's current version (the marker and the planner
  // need no more), and RefreshMap the occupancy grid message too.
  void RefreshSnapshot();
  void RefreshMap();
  // With loop closure, RefreshSnapshot's work: the redrawn map brought up to date (redrawn after
  // a new solution, the new nodes added otherwise), and the snapshot from it. False (nothing
  // done) without loop closure.
  bool RefreshRedrawnSnapshot();

  NodeOptions options_;
  bool has_odometry_frame_;  // odom_frame != base_frame

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  ros::NodeHandle map_nh_;  // serviced by map_thread_
  ros::CallbackQueue map_queue_;
  // The map thread (MapLoop): snapshots, /map, the hex_map marker, the map services. Below the
  // scan path's priority: a redraw of the whole map after a loop closes takes tens of ms, and on
  // a busy machine it should wait for the scans, not they for it.
  std::thread map_thread_;
  std::atomic<bool> map_thread_stop_{false};
  // The scans' and tf's queue, serviced by scan_spinner_: tf2's listener would otherwise poll
  // its own queue 100 times a second on a thread of its own.
  ros::CallbackQueue scan_callback_queue_;
  ros::NodeHandle scan_nh_;
  ros::AsyncSpinner scan_spinner_;
  ScanQueue<ScanPtr> scan_queue_;
  std::thread slam_thread_;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;

  // Guards the Slam and what changes with it.
  std::mutex mutex_;
  Slam slam_;
  ScanClock scan_clock_;
  TrajectoryRecorder trajectory_;
  std::uint64_t map_generation_ = 0;  // bumped by every map change and reset
  // What the map thread's snapshot lacks: the world box of the updates since its last refresh,
  // or everything (after a reset or a loaded map).
  Eigen::AlignedBox2d changed_region_;
  bool snapshot_stale_ = true;
  std::optional<io::HexMapData> saved_map_;  // map_file's contents, restored after every reset
  // An initialpose to apply with the next scan: the pose, and the odometry at its stamp, which
  // carries it forward to the scan's stamp.
  struct PendingPose {
    Pose2 pose;
    std::optional<Pose2> odom_to_base;
  };
  std::optional<PendingPose> pending_pose_;
  std::optional<Pose2> core_odometry_;  // the odometry the core saw with its previous scan

  // SLAM-thread state (one thread, no lock).
  TfHelper tf_helper_;
  std::optional<geometry_msgs::TransformStamped> last_map_transform_;  // map->odom or map->base
  ros::Time last_tf_stamp_;  // tf listeners reject a stamp twice or going back
  bool odometry_seen_ = false;     // odom->base has been in tf at least once
  bool odometry_missing_warned_ = false;
  std::optional<TrackingState> published_state_;  // on tracking_state
  // Wall s between the scans' arrivals (smoothed): the time each may take; 0 until known.
  double scan_period_ = 0.0;
  std::optional<std::chrono::steady_clock::time_point> previous_receipt_;
  std::atomic<bool> paused_{false};  // also read by the map thread's diagnostics

  // Written by the SLAM thread and the subscriber, read by the map thread's diagnostics.
  std::mutex stats_mutex_;
  ScanStats stats_;

  // Map-thread state (one thread, no lock).
  std::optional<RedrawnMap> redrawn_;  // with loop closure: what the map outputs show
  MapSnapshot snapshot_;
  bool have_snapshot_ = false;
  nav_msgs::OccupancyGrid map_msg_;
  std::uint64_t map_msg_generation_ = 0;
  bool have_map_msg_ = false;
  std::uint64_t marker_generation_ = 0;
  bool have_marker_ = false;
  long reported_drops_ = 0;
  double snapshot_ms_ = 0.0;      // the latest snapshot refresh, under mutex_
  double snapshot_ms_max_ = 0.0;  // the longest one
  double raster_ms_ = 0.0;        // the latest rasterisation, outside it

  ros::Subscriber scan_sub_, command_sub_, initial_pose_sub_;
  ros::Publisher pose_pub_, pose_update_pub_, odometry_pub_, map_pub_, map_metadata_pub_,
      hex_map_pub_, trajectory_pub_, diagnostics_pub_, tracking_state_pub_;
  ros::ServiceServer reset_service_, restart_service_, pause_service_, dynamic_map_service_,
      save_map_service_;
  ros::ServiceServer plan_service_;
  ros::Publisher slam_cloud_pub_;  // hector's slam_cloud, filled only with a subscriber
  ros::Publisher planned_path_pub_;
  ros::Subscriber goal_sub_;
  // Wall-clock periods: a bag played fast or a simulator's clock would otherwise wake the map
  // thread at every /clock message and publish maps as often as the clock runs.
  ros::WallTimer map_timer_, hex_map_timer_;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_SLAM_NODE_H_
