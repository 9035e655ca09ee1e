#include "slam_node.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/MapMetaData.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <visualization_msgs/Marker.h>

#include "hex_slam/common/input_limits.h"
#include "ros_input/msg_conversion.h"
#include "scan_msgs.h"
#include "slam_node_internal.h"

namespace hex_slam {
namespace node {
namespace {

using internal::kWarnPeriod;
using internal::MillisecondsSince;

// A laser whose scan plane leaves the base's plane by more than this (rad) sees the floor or
// misses walls; its points are projected and height-filtered, but the user should know.
constexpr double kTiltWarning = 0.05;
// Latched topics and hector's queue lengths, but for the poses: one per scan, and a bag replayed
// faster than real time (or two scans stamped 1 us apart) delivers scans in bursts, so hector's
// queue of 1 let a subscriber recording the trajectory lose poses (14 of 800 in the Intel
// replay test).
constexpr int kPoseQueue = 50;
constexpr int kOdometryQueue = 50;
constexpr int kCommandQueue = 2;
// ROS's own queue in front of the ScanQueue: the subscriber thread empties it at once, so it only
// has to absorb that thread's scheduling delays.
constexpr int kScanTransportQueue = 100;
// The scan period estimate follows the scans' arrivals with this weight per scan.
constexpr double kPeriodSmoothing = 0.1;
// A tf wait never drops below this (s): odometry published right after its scan still makes it.
constexpr double kMinTfWait = 0.005;

// A scan stamped this far ahead of the node's clock comes from a broken clock, not a lidar: taken
// in, it would make every later scan look a restart (and reset the map).
constexpr double kMaxStampLead = 3600.0;  // s
// tf2 adds its cache length to stamps: one within a day of the end of ROS time overflows it.
constexpr std::uint32_t kLastUsableSecond = std::numeric_limits<std::uint32_t>::max() - 86400;

// Why a scan's stamp cannot be used; empty when it can. `now` is zero while a simulated clock
// has not started.
std::string StampProblem(const ros::Time& stamp, const ros::Time& now) {
  if (stamp.sec > kLastUsableSecond) return "too close to the end of ROS time";
  if (!now.isZero() && stamp.toSec() > now.toSec() + kMaxStampLead) {
    return "more than an hour ahead of the clock";
  }
  return "";
}

ros::NodeHandle WithQueue(ros::NodeHandle nh, ros::CallbackQueue* queue) {
  nh.setCallbackQueue(queue);
  return nh;
}

}  // namespace

SlamNode::SlamNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                   const NodeConfig& config)
    : options_(config.node),
      has_odometry_frame_(config.node.odom_frame != config.node.base_frame),
      nh_(nh),
      private_nh_(private_nh),
      map_nh_(nh),
      scan_nh_(WithQueue(nh, &scan_callback_queue_)),
      scan_spinner_(1, &scan_callback_queue_),
      scan_queue_(static_cast<std::size_t>(config.node.scan_subscriber_queue_size)),
      tf_listener_(tf_buffer_, scan_nh_, false),
      slam_(config.slam),
      scan_clock_(config.node.time_jump_reset_threshold),
      trajectory_(config.node.trajectory_min_distance, config.node.trajectory_min_angle,
                  config.node.trajectory_max_poses),
      tf_helper_(&tf_buffer_, config.node.base_frame) {
  map_nh_.setCallbackQueue(&map_queue_);
  if (options_.map_pub_resolution <= 0.0) options_.map_pub_resolution = config.slam.map_resolution;
  const NodeOptions& o = options_;

  pose_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("slam_out_pose", kPoseQueue);
  pose_update_pub_ =
      nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>(o.pose_update_topic, kPoseQueue);
  if (o.pub_odometry) {
    odometry_pub_ = nh_.advertise<nav_msgs::Odometry>("scanmatch_odom", kOdometryQueue);
  }
  map_pub_ = nh_.advertise<nav_msgs::OccupancyGrid>("map", 1, true);
  map_metadata_pub_ = nh_.advertise<nav_msgs::MapMetaData>("map_metadata", 1, true);
  hex_map_pub_ = nh_.advertise<visualization_msgs::Marker>("hex_map", 1, true);
  trajectory_pub_ = nh_.advertise<nav_msgs::Path>("trajectory", 1, true);
  diagnostics_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 1);
  tracking_state_pub_ = nh_.advertise<std_msgs::String>("tracking_state", 1, true);
  slam_cloud_pub_ = nh_.advertise<sensor_msgs::PointCloud>("slam_cloud", 1);

  ROS_INFO("hex_slam: %s lattice, map_resolution %.4f m, /map pixels %.4f m; frames map '%s', "
           "odom '%s', base '%s'; scans on '%s' (queue %d)%s%s",
           config.slam.lattice.c_str(), config.slam.map_resolution, o.map_pub_resolution,
           o.map_frame.c_str(), o.odom_frame.c_str(), o.base_frame.c_str(),
           nh_.resolveName(o.scan_topic).c_str(), o.scan_subscriber_queue_size,
           has_odometry_frame_ && o.use_odometry ? ", odometry prior from tf" : "",
           config.slam.map_with_known_poses ? "; map_with_known_poses: no matching, no pose out"
                                            : "");
}

void SlamNode::Start() {
  // The map (empty, or map_file's) is latched before anything can ask for it, as hector does.
  PublishInitialMap();
  TrackingState state;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    state = slam_.tracking_state();
  }
  PublishTrackingState(state);
  AdvertiseCommands();
  AdvertiseMapOutput();
  slam_thread_ = std::thread(&SlamNode::ScanLoop, this);
  scan_sub_ = scan_nh_.subscribe(options_.scan_topic, kScanTransportQueue,
                                 &SlamNode::OnScanReceived, this);
  scan_spinner_.start();
}

void SlamNode::AdvertiseCommands() {
  command_sub_ =
      nh_.subscribe(options_.sys_msg_topic, kCommandQueue, &SlamNode::OnSysCommand, this);
  initial_pose_sub_ = nh_.subscribe("initialpose", kCommandQueue, &SlamNode::OnInitialPose, this);
  reset_service_ = nh_.advertiseService("reset_map", &SlamNode::OnResetMap, this);
  restart_service_ =
      nh_.advertiseService("restart_mapping_with_new_pose", &SlamNode::OnRestartWithPose, this);
  pause_service_ = nh_.advertiseService("pause_mapping", &SlamNode::OnPauseMapping, this);
}

void SlamNode::AdvertiseMapOutput() {
  const NodeOptions& o = options_;
  if (o.advertise_map_service) {
    dynamic_map_service_ = map_nh_.advertiseService("dynamic_map", &SlamNode::OnDynamicMap, this);
  }
  save_map_service_ = map_nh_.advertiseService("save_map", &SlamNode::OnSaveMap, this);
  plan_service_ = map_nh_.advertiseService("plan_path", &SlamNode::OnPlanPath, this);
  planned_path_pub_ = map_nh_.advertise<nav_msgs::Path>("planned_path", 1, true);
  if (o.plan_on_goal) {
    goal_sub_ = map_nh_.subscribe("move_base_simple/goal", kCommandQueue, &SlamNode::OnGoal, this);
  }
  map_timer_ =
      map_nh_.createWallTimer(ros::WallDuration(o.map_pub_period), &SlamNode::OnMapTimer, this);
  if (o.hex_map_pub_period > 0.0) {
    hex_map_timer_ = map_nh_.createWallTimer(ros::WallDuration(o.hex_map_pub_period),
                                             &SlamNode::OnHexMapTimer, this);
  }
  map_thread_ = std::thread(&SlamNode::MapLoop, this);
}

SlamNode::~SlamNode() {
  scan_spinner_.stop();
  scan_queue_.Close();
  if (slam_thread_.joinable()) slam_thread_.join();
  map_thread_stop_ = true;
  if (map_thread_.joinable()) map_thread_.join();
}

ScanStats SlamNode::stats() {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

long SlamNode::CountDrop(long DropCounters::*counter) {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return ++(stats_.drops.*counter);
}

void SlamNode::OnScanReceived(const ScanPtr& msg) {
  bool dropped = false;
  scan_queue_.Push(msg, &dropped);
  if (!dropped) return;
  const long count = CountDrop(&DropCounters::queue_overflow);
  ROS_WARN_THROTTLE(kWarnPeriod,
                    "hex_slam: falling behind the scans: dropped the oldest waiting scan (%ld so "
                    "far; scan_subscriber_queue_size %d)",
                    count, options_.scan_subscriber_queue_size);
}

void SlamNode::ScanLoop() {
  while (std::optional<ScanQueue<ScanPtr>::Entry> entry = scan_queue_.Pop()) {
    ProcessScanMessage(*entry->item, entry->received);
  }
}

double SlamNode::TfWait() const {
  if (scan_period_ <= 0.0) return options_.tf_timeout;
  return std::min(options_.tf_timeout, std::max(kMinTfWait, scan_period_));
}

bool SlamNode::MountAt(const sensor_msgs::LaserScan& msg, SensorMount* mount) {
  if (!options_.use_tf_scan_transformation) {
    *mount = SensorMount();
    return true;
  }
  const std::string frame = CleanFrameId(msg.header.frame_id);
  std::string error;
  const std::optional<MountLookup> found =
      tf_helper_.Mount(frame, msg.header.stamp, TfWait(), options_.tf_timeout, &error);
  if (!found) {
    const long count = CountDrop(&DropCounters::no_laser_transform);
    ROS_WARN_THROTTLE(kWarnPeriod,
                      "hex_slam: dropping scan: no transform from its frame '%s' to '%s' (%s); "
                      "%ld scans dropped for this so far",
                      frame.c_str(), options_.base_frame.c_str(), error.c_str(), count);
    return false;
  }
  ROS_INFO_ONCE("hex_slam: laser '%s' at (%.3f, %.3f) m, yaw %.3f rad on '%s'%s", frame.c_str(),
                found->planar.x, found->planar.y, found->planar.theta,
                options_.base_frame.c_str(), found->upside_down ? ", upside down" : "");
  if (found->tilt > kTiltWarning) {
    ROS_WARN_THROTTLE(kWarnPeriod * 12,
                      "hex_slam: laser '%s' is tilted %.3f rad from the base's plane: its points "
                      "are projected onto it, those outside (laser_z_min_value, "
                      "laser_z_max_value) above the laser ignored",
                      frame.c_str(), found->tilt);
  }
  *mount = found->mount;
  return true;
}

bool SlamNode::AdmitStamp(const LaserScan& scan) {
  const StampOrder order = scan_clock_.Check(scan.stamp);
  if (order == StampOrder::kInOrder) return true;
  const double back = *scan_clock_.last() - scan.stamp;
  if (order == StampOrder::kSlightlyEarlier) {
    const long count = CountDrop(&DropCounters::late);
    ROS_WARN_THROTTLE(kWarnPeriod,
                      "hex_slam: dropping a scan stamped %.3f s before the previous one (%ld so "
                      "far); more than time_jump_reset_threshold = %.2f s would reset the map",
                      back, count, options_.time_jump_reset_threshold);
    return false;
  }
  // A restart: but only a well-formed scan may wipe the map.
  std::vector<Eigen::Vector2d> points;
  BeamCounts counts;
  std::string message;
  if (SanitizeScan(scan, RangeFilter(), &points, &counts, &message) != ScanError::kNone) {
    CountDrop(&DropCounters::invalid);
    ROS_WARN_THROTTLE(kWarnPeriod, "hex_slam: dropping an invalid scan: %s", message.c_str());
    return false;
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.time_jump_resets;
  }
  ROS_WARN("hex_slam: scan stamped %.3f s before the previous one: the source restarted (a bag "
           "played again?); resetting the map", back);
  ResetLocked(Pose2());
  last_tf_stamp_ = ros::Time();
  return true;
}

std::optional<Pose2> SlamNode::OdometryAt(const ros::Time& stamp) {
  if (!has_odometry_frame_ || !(options_.use_odometry || options_.pub_map_odom_transform)) {
    return std::nullopt;
  }
  // An odometry frame tf cannot reach at all (hector's launch files name one, "nav", that often
  // nothing publishes) is not waited for: every scan would lose tf_timeout to it.
  if (!tf_helper_.Connected(options_.odom_frame, options_.base_frame)) {
    if (!odometry_seen_ && !odometry_missing_warned_) {
      odometry_missing_warned_ = true;
      ROS_WARN("hex_slam: tf has no %s->%s: matching without odometry and publishing %s->%s as "
               "if odometry were the identity (as hector_mapping does) until it appears",
               options_.odom_frame.c_str(), options_.base_frame.c_str(),
               options_.map_frame.c_str(), options_.odom_frame.c_str());
    }
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.no_odometry;
    return std::nullopt;
  }
  std::string error;
  const std::optional<Pose2> odom_to_base = tf_helper_.Lookup(
      options_.odom_frame, options_.base_frame, stamp, TfWait(), &error);
  if (odom_to_base) {
    if (!odometry_seen_) {
      ROS_INFO("hex_slam: odometry %s->%s found", options_.odom_frame.c_str(),
               options_.base_frame.c_str());
    }
    odometry_seen_ = true;
    return odom_to_base;
  }
  long count;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    count = ++stats_.no_odometry;
  }
  ROS_WARN_THROTTLE(kWarnPeriod,
                    "hex_slam: no odometry %s->%s at the scan's stamp (%s); matching without "
                    "it (%ld times so far; a robot without odometry needs odom_frame = "
                    "base_frame)",
                    options_.odom_frame.c_str(), options_.base_frame.c_str(), error.c_str(),
                    count);
  return std::nullopt;
}

std::optional<Pose2> SlamNode::LateOdometryAt(const ros::Time& stamp) const {
  // The scan was matched without odometry that had not come within TfWait (a relay or a busy
  // machine lags it). It often has by now: map->odom from it agrees with the published pose,
  // where the last correction would put map->base off it by this scan's correction.
  if (!odometry_seen_) return std::nullopt;
  std::string error;
  return tf_helper_.Lookup(options_.odom_frame, options_.base_frame, stamp, 0.0, &error);
}

std::optional<Pose2> SlamNode::StartEstimateAt(const ros::Time& stamp) {
  if (!options_.use_tf_pose_start_estimate) return std::nullopt;
  // Never waited for: when this node publishes map->odom itself, map->base at this stamp only
  // exists once this scan is processed, and waiting would delay every scan by tf_timeout.
  std::string error;
  const std::optional<Pose2> estimate =
      tf_helper_.Lookup(options_.map_frame, options_.base_frame, stamp, 0.0, &error);
  if (!estimate) {
    ROS_WARN_THROTTLE(kWarnPeriod,
                      "hex_slam: use_tf_pose_start_estimate: no %s->%s at the scan's stamp "
                      "(%s); starting from the previous estimate",
                      options_.map_frame.c_str(), options_.base_frame.c_str(), error.c_str());
  }
  return estimate;
}

void SlamNode::ProcessScanMessage(const sensor_msgs::LaserScan& msg,
                                  std::chrono::steady_clock::time_point received) {
  const auto start = std::chrono::steady_clock::now();
  const ros::Time stamp = msg.header.stamp;
  const std::string stamp_problem = StampProblem(stamp, ros::Time::now());
  if (!stamp_problem.empty()) {
    const long count = CountDrop(&DropCounters::invalid);
    ROS_WARN_THROTTLE(kWarnPeriod, "hex_slam: dropping a scan stamped %u.%09u: %s (%ld so far)",
                      stamp.sec, stamp.nsec, stamp_problem.c_str(), count);
    return;
  }
  if (paused_) {
    CountDrop(&DropCounters::paused);
    RepublishTransforms(stamp);
    return;
  }
  if (previous_receipt_) {
    const double step = std::chrono::duration<double>(received - *previous_receipt_).count();
    scan_period_ = scan_period_ > 0.0 ? scan_period_ + kPeriodSmoothing * (step - scan_period_)
                                      : step;
  }
  previous_receipt_ = received;
  SensorMount mount;
  if (!MountAt(msg, &mount)) return;

  const std::optional<Pose2> odom_to_base = OdometryAt(stamp);
  const std::optional<Pose2> start_estimate = StartEstimateAt(stamp);
  const LaserScan scan = ScanFromMsg(msg, msg.header.stamp.toSec());
  if (slam_cloud_pub_.getNumSubscribers() > 0) {
    slam_cloud_pub_.publish(
        ToPointCloudMsg(msg, slam_.options().laser_min_dist, slam_.options().laser_max_dist));
  }
  const std::optional<Pose2> prior = options_.use_odometry ? odom_to_base : std::nullopt;

  ScanReport report;
  double core_ms = 0.0;
  bool invalid = false;
  long times_lost = 0, relocalizations = 0, restarts = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Checked again here: paused while this scan waited for tf, a reset may since have cleared
    // the map, and the scan must not start a new one.
    if (paused_) {
      CountDrop(&DropCounters::paused);
      return;
    }
    if (!AdmitStamp(scan)) return;
    if (pending_pose_) {
      Pose2 target = pending_pose_->pose;
      if (pending_pose_->odom_to_base && odom_to_base) {
        target = target * RelativePose(*pending_pose_->odom_to_base, *odom_to_base);
      }
      StartScanAt(target, prior);
      pending_pose_.reset();
    } else if (start_estimate) {
      StartScanAt(*start_estimate, prior);
    }
    const auto core_start = std::chrono::steady_clock::now();
    try {
      report = slam_.ProcessScan(scan, mount, prior, /*defer_map_update=*/true);
    } catch (const std::exception& e) {
      CountDrop(&DropCounters::errors);
      ROS_ERROR_THROTTLE(kWarnPeriod, "hex_slam: scan processing failed: %s", e.what());
      return;
    }
    core_ms = MillisecondsSince(core_start);
    times_lost = slam_.times_lost();
    relocalizations = slam_.relocalizations();
    restarts = slam_.restarts();
    invalid = report.outcome == ScanOutcome::kInvalidScan ||
              report.outcome == ScanOutcome::kTimeWentBackwards;
    if (!invalid) {
      if (prior) core_odometry_ = prior;
      scan_clock_.Accept(scan.stamp);
      // The first scan, which defines the map, is never deferred.
      if (report.map_updated) NoteMapChanged(report.updated_region);
      if (report.tracking_state != TrackingState::kLost) {
        trajectory_.Add(scan.stamp, report.global_pose);
      }
    }
  }
  if (invalid) {
    const long count = CountDrop(&DropCounters::invalid);
    ROS_WARN_THROTTLE(kWarnPeriod, "hex_slam: dropping a scan (%s): %s; %ld so far",
                      ScanOutcomeName(report.outcome), report.message.c_str(), count);
    RepublishTransforms(stamp);
    return;
  }
  if (report.outcome == ScanOutcome::kTooFewPoints) {
    ROS_WARN_THROTTLE(kWarnPeriod, "hex_slam: not matching a scan: %s", report.message.c_str());
  }
  NoteTracking(report, times_lost, relocalizations, restarts);
  // hector_mapping with map_with_known_poses maps at the given poses and publishes no pose and
  // no tf: the poses are someone else's.
  // With loop closure the map frame is the pose graph's: the front end's pose moved by the latest
  // optimisation's correction (read from the worker's board, never waited for), so map->odom
  // follows each optimisation from the next scan on. Without it global_pose == pose.
  if (!slam_.options().map_with_known_poses) {
    PublishPose(report, stamp);
    // Lost: the last good correction stays (odometry carries the robot on from it).
    if (report.tracking_state == TrackingState::kLost) {
      RepublishTransforms(stamp, true);
    } else {
      PublishTransforms(report.global_pose, odom_to_base, stamp);
    }
  }
  // The pose is out: the scan goes into the map now (InsertDeferredScan), off the latency.
  const auto done = std::chrono::steady_clock::now();
  if (report.map_update_deferred) InsertDeferredScan(&report);
  const double work_ms = MillisecondsSince(start);
  const double latency_ms = std::chrono::duration<double, std::milli>(done - received).count();
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.timing.Add(work_ms, core_ms, latency_ms);
  }
  if (options_.output_timing) {
    ROS_INFO("hex_slam: scan took %.3f ms (core %.3f ms, %s), %.3f ms after it arrived", work_ms,
             core_ms, ScanOutcomeName(report.outcome), latency_ms);
  }
}

void SlamNode::InsertDeferredScan(ScanReport* report) {
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    if (!slam_.InsertDeferredScan(report)) return;  // a reset or a new pose came in between
  } catch (const std::exception& e) {
    CountDrop(&DropCounters::errors);
    ROS_ERROR_THROTTLE(kWarnPeriod, "hex_slam: inserting a scan into the map failed: %s", e.what());
    return;
  }
  NoteMapChanged(report->updated_region);
}

void SlamNode::NoteMapChanged(const Eigen::AlignedBox2d& region) {
  ++map_generation_;
  changed_region_.extend(region);
}

void SlamNode::NoteTracking(const ScanReport& report, long times_lost, long relocalizations,
                            long restarts) {
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    TrackingStats& k = stats_.tracking;
    k.state = TrackingStateName(report.tracking_state);
    k.reason = report.tracking_reason;
    if (report.score.scored()) k.match_score = report.score.score;
    k.sigma_x = std::sqrt(report.covariance(0, 0));
    k.sigma_y = std::sqrt(report.covariance(1, 1));
    k.sigma_yaw = std::sqrt(report.covariance(2, 2));
    switch (report.tracking_state) {
      case TrackingState::kOk: ++k.scans_ok; break;
      case TrackingState::kDegraded: ++k.scans_degraded; break;
      case TrackingState::kLost: ++k.scans_lost; break;
    }
    k.times_lost = times_lost;
    k.relocalizations = relocalizations;
    k.restarts = restarts;
  }
  if (published_state_ == report.tracking_state) return;
  const char* name = TrackingStateName(report.tracking_state);
  switch (report.tracking_state) {
    case TrackingState::kOk:
      ROS_INFO("hex_slam: tracking ok: %s", report.tracking_reason.c_str());
      break;
    case TrackingState::kDegraded:
      ROS_WARN("hex_slam: tracking degraded: %s", report.tracking_reason.c_str());
      break;
    case TrackingState::kLost:
      ROS_ERROR("hex_slam: tracking %s: %s; publishing no slam_out_pose and no new tf, not "
                "updating the map, searching for the robot", name,
                report.tracking_reason.c_str());
      break;
  }
  PublishTrackingState(report.tracking_state);
}

void SlamNode::PublishTrackingState(TrackingState state) {
  std_msgs::String msg;
  msg.data = TrackingStateName(state);
  tracking_state_pub_.publish(msg);
  published_state_ = state;
}

void SlamNode::PublishPose(const ScanReport& report, const ros::Time& stamp) {
  // The core never reports a pose or covariance that is not finite; this is the last guard.
  if (!IsFinite(report.global_pose) || !report.covariance.allFinite()) {
    CountDrop(&DropCounters::errors);
    ROS_ERROR_THROTTLE(kWarnPeriod, "hex_slam: not publishing a pose that is not finite");
    return;
  }
  geometry_msgs::PoseWithCovarianceStamped pose;
  pose.header.stamp = stamp;
  pose.header.frame_id = options_.map_frame;
  pose.pose.pose = ToPoseMsg(report.global_pose);
  pose.pose.covariance = ToCovarianceMsg(report.covariance);
  geometry_msgs::PoseStamped plain;
  plain.header = pose.header;
  plain.pose = pose.pose.pose;
  if (report.tracking_state != TrackingState::kLost) pose_pub_.publish(plain);
  pose_update_pub_.publish(pose);
  if (options_.pub_odometry) {
    nav_msgs::Odometry odometry;
    odometry.header = pose.header;
    odometry.child_frame_id = options_.base_frame;
    odometry.pose = pose.pose;
    odometry_pub_.publish(odometry);
  }
}

void SlamNode::PublishTransforms(const Pose2& pose, const std::optional<Pose2>& odom_to_base,
                                 const ros::Time& stamp) {
  if (stamp <= last_tf_stamp_) return;
  std::vector<geometry_msgs::TransformStamped> transforms;
  if (options_.pub_map_odom_transform) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = options_.map_frame;
    if (!has_odometry_frame_) {
      t.child_frame_id = options_.base_frame;
      t.transform = ToTransformMsg(pose);
    } else if (const std::optional<Pose2> odom = odom_to_base ? odom_to_base
                                                              : LateOdometryAt(stamp)) {
      t.child_frame_id = options_.odom_frame;
      t.transform = ToTransformMsg(pose * odom->inverse());
    } else if (odometry_seen_ && last_map_transform_) {
      t = *last_map_transform_;  // odometry missing this once: keep the last correction
      t.header.stamp = stamp;
    } else {
      t.child_frame_id = options_.odom_frame;  // no odometry at all: hector's identity
      t.transform = ToTransformMsg(pose);
    }
    transforms.push_back(t);
    last_map_transform_ = t;
  }
  if (options_.pub_map_scanmatch_transform) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = options_.map_frame;
    t.child_frame_id = options_.tf_map_scanmatch_transform_frame_name;
    t.transform = ToTransformMsg(pose);
    transforms.push_back(t);
  }
  if (transforms.empty()) return;
  tf_broadcaster_.sendTransform(transforms);
  last_tf_stamp_ = stamp;
}

void SlamNode::RepublishTransforms(const ros::Time& stamp, bool holding) {
  // map->base follows the robot only with new scans: republishing it would freeze the robot,
  // which is right only while the core holds it still.
  if (!last_map_transform_ || (!has_odometry_frame_ && !holding) || stamp <= last_tf_stamp_) {
    return;
  }
  geometry_msgs::TransformStamped t = *last_map_transform_;
  t.header.stamp = stamp;
  tf_broadcaster_.sendTransform(t);
  last_tf_stamp_ = stamp;
}

void SlamNode::StartScanAt(Pose2 target, const std::optional<Pose2>& prior) {
  if (prior && core_odometry_) target = target * RelativePose(*prior, *core_odometry_);
  if (!slam_.SetPose(target)) {
    ROS_WARN("hex_slam: ignoring the pose (%g, %g) m, %g rad: not finite, or out of the map's "
             "reach; the estimate stays where it was", target.x, target.y, target.theta);
  }
}

void SlamNode::PublishInitialMap() {
  RefreshMap();  // the map thread is not running yet
  map_msg_.header.stamp = ros::Time::now();
  map_pub_.publish(map_msg_);
  map_metadata_pub_.publish(map_msg_.info);
}

std::string SlamNode::LoadMapFile() {
  if (options_.map_file.empty()) return "";
  io::HexMapData data;
  std::string error = io::ReadHexMapFile(options_.map_file, &data);
  std::lock_guard<std::mutex> lock(mutex_);
  if (error.empty()) error = io::RestoreSlamMap(data, &slam_);
  if (!error.empty()) return "map_file " + options_.map_file + ": " + error;
  saved_map_ = std::move(data);
  ++map_generation_;
  snapshot_stale_ = true;
  ROS_INFO("hex_slam: map loaded from %s (%s); set the robot's pose with initialpose",
           options_.map_file.c_str(),
           slam_.options().update_map ? "mapping goes on from it" : "localization only");
  return "";
}

void SlamNode::ResetLocked(const Pose2& pose) {
  slam_.Reset(pose);
  // A restore that worked at start-up works again: same file contents, same options.
  if (saved_map_) io::RestoreSlamMap(*saved_map_, &slam_);
  core_odometry_.reset();
  pending_pose_.reset();
  scan_clock_.Reset();
  trajectory_.Clear();
  ++map_generation_;
  snapshot_stale_ = true;
  changed_region_.setEmpty();
}

void SlamNode::OnSysCommand(const std_msgs::String::ConstPtr& msg) {
  if (msg->data != "reset") {
    ROS_INFO("hex_slam: ignoring command '%s' (only \"reset\" is understood)", msg->data.c_str());
    return;
  }
  ROS_INFO("hex_slam: reset by command");
  std::lock_guard<std::mutex> lock(mutex_);
  ResetLocked(Pose2());
}

void SlamNode::OnInitialPose(const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& msg) {
  PendingPose pending{PoseFromMsg(msg->pose.pose), std::nullopt};
  if (!std::isfinite(pending.pose.x) || !std::isfinite(pending.pose.y) ||
      !std::isfinite(pending.pose.theta)) {
    ROS_WARN("hex_slam: ignoring an initialpose that is not finite (NaN or inf)");
    return;
  }
  const std::string frame = CleanFrameId(msg->header.frame_id);
  std::string error;
  if (!frame.empty() && frame != options_.map_frame) {
    const std::optional<Pose2> frame_in_map =
        tf_helper_.Lookup(options_.map_frame, frame, ros::Time(0), 0.0, &error);
    if (!frame_in_map) {
      ROS_WARN("hex_slam: ignoring initialpose in frame '%s': %s", frame.c_str(), error.c_str());
      return;
    }
    pending.pose = *frame_in_map * pending.pose;
  }
  if (has_odometry_frame_ && !msg->header.stamp.isZero()) {
    // The robot moves on until the next scan: odometry carries the pose to that scan's stamp.
    pending.odom_to_base = tf_helper_.Lookup(options_.odom_frame, options_.base_frame,
                                             msg->header.stamp, options_.tf_timeout, &error);
  }
  ROS_INFO("hex_slam: pose set to (%.3f, %.3f) m, %.3f rad, from the next scan on",
           pending.pose.x, pending.pose.y, pending.pose.theta);
  std::lock_guard<std::mutex> lock(mutex_);
  pending_pose_ = pending;
}

bool SlamNode::OnResetMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ResetLocked(Pose2());
  }
  ROS_INFO("hex_slam: map reset by the reset_map service");
  response.success = true;
  response.message = saved_map_ ? "map reloaded from " + options_.map_file +
                                      "; the robot is at the origin until initialpose moves it"
                                : "map cleared; the next scan starts a new one at the origin";
  return true;
}

bool SlamNode::OnRestartWithPose(hex_slam::ResetMapping::Request& request,
                                 hex_slam::ResetMapping::Response&) {
  const Pose2 pose = PoseFromMsg(request.initial_pose);
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    ROS_WARN("hex_slam: restart_mapping_with_new_pose: the pose is not finite; nothing changed");
    return false;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ResetLocked(pose);
    pending_pose_ = PendingPose{pose, std::nullopt};
  }
  if (paused_) ROS_INFO("hex_slam: mapping resumed");
  paused_ = false;
  ROS_INFO("hex_slam: map cleared, restarting at (%.3f, %.3f) m, %.3f rad", pose.x, pose.y,
           pose.theta);
  return true;
}

bool SlamNode::OnPauseMapping(std_srvs::SetBool::Request& request,
                              std_srvs::SetBool::Response& response) {
  if (request.data != paused_) {
    ROS_INFO("hex_slam: mapping %s", request.data ? "paused" : "resumed");
  }
  paused_ = static_cast<bool>(request.data);
  response.success = true;
  response.message = request.data ? "paused" : "running";
  return true;
}

}  // namespace node
}  // namespace hex_slam
