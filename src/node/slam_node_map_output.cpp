// SlamNode's map thread: the snapshot, the occupancy grid and its metadata, the hex_map marker,
// the trajectory, the diagnostics, and the dynamic_map and save_map services. Nothing here runs
// on the scan callback's thread; the SLAM lock is held only to copy.
#include <algorithm>
#include <filesystem>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Path.h>

#include "map_output/hex_map_marker.h"
#include "hex_slam/common/thread_priority.h"
#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/logs/offline/resource_usage.h"
#include "map_output/map_saver.h"
#include "ros_input/msg_conversion.h"
#include "slam_node.h"
#include "slam_node_internal.h"

namespace hex_slam {
namespace node {

using internal::kWarnPeriod;
using internal::MillisecondsSince;

namespace {

// The map thread's nice value above the scan path's: below the scans, above the loop-closure
// worker (+10), whose solutions it draws.
constexpr int kMapThreadNicenessIncrement = 5;
// How long the map thread waits for a callback before it looks at the stop flag again (s).
constexpr double kMapQueueWait = 0.1;

}  // namespace

void SlamNode::MapLoop() {
  if (!LowerThisThreadPriority(kMapThreadNicenessIncrement)) {
    ROS_DEBUG("hex_slam: could not lower the map thread's priority; it runs beside the scans");
  }
  while (!map_thread_stop_ && nh_.ok()) map_queue_.callAvailable(ros::WallDuration(kMapQueueWait));
}

void SlamNode::RefreshSnapshot() {
  if (RefreshRedrawnSnapshot()) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (have_snapshot_ && snapshot_.generation == map_generation_) return;
  const auto start = std::chrono::steady_clock::now();
  UpdateSnapshot(slam_, changed_region_, snapshot_stale_, map_generation_, options_.hex_map_level,
                 &snapshot_);
  changed_region_.setEmpty();
  snapshot_stale_ = false;
  have_snapshot_ = true;
  snapshot_ms_ = MillisecondsSince(start);
  snapshot_ms_max_ = std::max(snapshot_ms_max_, snapshot_ms_);
}

bool SlamNode::RefreshRedrawnSnapshot() {
  NodeList nodes;
  std::shared_ptr<const mapping::PoseGraphSolution> solution;
  std::uint64_t generation = 0;
  bool stale = false;
  {
    // Only shared pointers are copied under the lock; the drawing runs outside it.
    std::lock_guard<std::mutex> lock(mutex_);
    if (!slam_.loop_closure_active()) {
      redrawn_.reset();
      return false;
    }
    const std::uint64_t version = slam_.solutions()->version();
    if (have_snapshot_ && redrawn_ && snapshot_.generation == map_generation_ &&
        redrawn_->solution() && redrawn_->solution()->version == version) {
      return true;
    }
    solution = slam_.solutions()->Get();
    // A new solution changes the map without a scan: a new map version for its consumers.
    if (!redrawn_ || redrawn_->solution() != solution) ++map_generation_;
    nodes = slam_.Nodes();
    generation = map_generation_;
    stale = snapshot_stale_;
    snapshot_stale_ = false;
    changed_region_.setEmpty();
  }
  const auto start = std::chrono::steady_clock::now();
  if (!redrawn_) redrawn_.emplace(slam_.options());
  Eigen::AlignedBox2d changed;
  bool all = false;
  redrawn_->Update(nodes, solution, &changed, &all);
  UpdateSnapshot(redrawn_->hex(), redrawn_->square(), changed, all || stale || !have_snapshot_,
                 generation, options_.hex_map_level, &snapshot_);
  have_snapshot_ = true;
  snapshot_ms_ = MillisecondsSince(start);
  snapshot_ms_max_ = std::max(snapshot_ms_max_, snapshot_ms_);
  return true;
}

void SlamNode::RefreshMap() {
  RefreshSnapshot();
  if (have_map_msg_ && map_msg_generation_ == snapshot_.generation) return;
  const auto start = std::chrono::steady_clock::now();
  map_msg_ = ToOccupancyGridMsg(RasterizeSnapshot(snapshot_, options_.map_pub_resolution),
                                options_.map_frame, ros::Time::now());
  raster_ms_ = MillisecondsSince(start);
  map_msg_generation_ = snapshot_.generation;
  have_map_msg_ = true;
}

void SlamNode::OnMapTimer(const ros::WallTimerEvent&) {
  RefreshMap();
  map_msg_.header.stamp = ros::Time::now();
  map_pub_.publish(map_msg_);
  map_metadata_pub_.publish(map_msg_.info);

  nav_msgs::Path path;
  path.header.stamp = map_msg_.header.stamp;
  path.header.frame_id = options_.map_frame;
  std::vector<io::StampedPose> poses;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    poses = trajectory_.poses();
  }
  path.poses.resize(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    path.poses[i].header.frame_id = options_.map_frame;
    path.poses[i].header.stamp = ros::Time(poses[i].stamp);
    path.poses[i].pose = ToPoseMsg(poses[i].pose);
  }
  trajectory_pub_.publish(path);
  PublishDiagnostics();
}

void SlamNode::PublishDiagnostics() {
  MapStats map;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    map.scans_processed = slam_.scans_processed();
    map.map_updates = slam_.map_updates();
    map.recoveries = slam_.recoveries();
    map.memory_bytes = slam_.MemoryBytes();
    map.levels = slam_.hex_maps() ? slam_.hex_maps()->size() : slam_.square_maps()->size();
    map.loop_closure = slam_.loop_closure_active();
    if (map.loop_closure) map.loop = slam_.loop_closure_stats();
    map.global = slam_.global_localization_stats();
  }
  if (redrawn_) {
    map.map_redraws = redrawn_->redraws();
    map.map_redraw_ms = redrawn_->last_redraw_ms();
    map.map_solution_version = redrawn_->solution() ? redrawn_->solution()->version : 0;
  }
  const ScanStats scans = stats();
  map.paused = paused_;
  map.snapshot_ms = snapshot_ms_;
  map.snapshot_ms_max = snapshot_ms_max_;
  map.peak_resident_mb = logs::PeakResidentMegabytes();
  map.raster_ms = raster_ms_;
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  array.status.push_back(MakeDiagnostics(ros::this_node::getName() + ": scan matching", scans,
                                         map, reported_drops_));
  reported_drops_ = scans.drops.total();
  diagnostics_pub_.publish(array);
}

void SlamNode::OnHexMapTimer(const ros::WallTimerEvent&) {
  if (hex_map_pub_.getNumSubscribers() == 0) return;
  RefreshSnapshot();
  if (have_marker_ && marker_generation_ == snapshot_.generation) return;  // latched already
  MarkerStyle style;
  style.max_cells = options_.hex_map_max_cells;
  MarkerStats stats;
  hex_map_pub_.publish(
      MakeHexMapMarker(snapshot_, style, options_.map_frame, ros::Time::now(), &stats));
  marker_generation_ = snapshot_.generation;
  have_marker_ = true;
  if (stats.drawn_cells < stats.known_cells) {
    ROS_WARN_THROTTLE(kWarnPeriod * 12,
                      "hex_slam: hex_map shows %d of %d known cells (hex_map_max_cells)",
                      stats.drawn_cells, stats.known_cells);
  }
}

bool SlamNode::OnDynamicMap(nav_msgs::GetMap::Request&, nav_msgs::GetMap::Response& response) {
  RefreshMap();
  response.map = map_msg_;
  response.map.header.stamp = ros::Time::now();
  return true;
}

bool SlamNode::OnSaveMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  io::HexMapData cells;
  if (RefreshRedrawnSnapshot()) {
    // With loop closure both files are the redrawn map, drawn at the solution they keep.
    cells = redrawn_->hex() ? io::CaptureHexMap(*redrawn_->hex())
                            : io::CaptureHexMap(*redrawn_->square());
    cells.graph = io::CaptureGraph(*redrawn_->solution());
  } else {
    {
      // The same map version for both files: the snapshot is brought to the version captured.
      std::lock_guard<std::mutex> lock(mutex_);
      cells = io::CaptureSlamMap(slam_);
    }
    RefreshSnapshot();
  }
  // Absolute, so the reply says where the files went whatever the node's working directory.
  std::error_code no_cwd;
  const std::filesystem::path absolute = std::filesystem::absolute(options_.map_file_base, no_cwd);
  const std::string base = no_cwd ? options_.map_file_base : absolute.string();
  std::vector<std::string> written;
  const std::string error = SaveMapFiles(base, RasterizeSnapshot(snapshot_, options_.map_pub_resolution), cells,
                                         &written);
  response.success = error.empty();
  if (error.empty()) {
    response.message = "wrote";
    for (const std::string& path : written) response.message += " " + path;
    ROS_INFO("hex_slam: save_map %s", response.message.c_str());
  } else {
    response.message = "save_map failed: " + error;
    ROS_ERROR("hex_slam: %s", response.message.c_str());
  }
  return true;
}

}  // namespace node
}  // namespace hex_slam
