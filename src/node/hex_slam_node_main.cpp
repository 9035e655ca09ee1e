// hex_slam_node: a drop-in replacement for hector_mapping's node. Reads its private parameters
// once, refuses to start on nonsense values (naming the key), warns about keys it does not know,
// then maps until shut down and logs what the scan callback cost against the bare core.
#include <cmath>
#include <cstdio>

#include <ros/ros.h>

#include "hex_slam/common/heap_retention.h"
#include "node_options.h"
#include "rosparam_reader.h"
#include "slam_node.h"

namespace {

// Below this coarsest cell (m), a robot without odometry that moves more than about a cell
// between scans (0.2 m: a 5 Hz log at 1 m/s) can be lost: the coarsest cell is the basin the
// matcher converges from (docs/real_logs.md).
constexpr double kSmallCoarsestCell = 0.15;

// Says which levels are built, and why when they differ from map_multi_res_levels.
void LogMapLevels(const hex_slam::SlamOptions& slam, const hex_slam::node::NodeOptions& node) {
  const int levels = hex_slam::EffectiveLevels(slam);
  const double coarsest = slam.map_resolution * std::ldexp(1.0, levels - 1);
  ROS_INFO("hex_slam: %d map levels (map_multi_res_levels %d): cells %.3f to %.3f m", levels,
           slam.map_multi_res_levels, slam.map_resolution, coarsest);
  if (levels != slam.map_multi_res_levels) {
    ROS_WARN("hex_slam: map_multi_res_levels %d became %d to keep the coarsest cell within "
             "[map_min_coarse_resolution %.3f, map_max_coarse_resolution %.3f] m",
             slam.map_multi_res_levels, levels, slam.map_min_coarse_resolution,
             slam.map_max_coarse_resolution);
  }
  const bool odometry = node.use_odometry && node.odom_frame != node.base_frame;
  if (coarsest < kSmallCoarsestCell && !odometry && !slam.map_with_known_poses) {
    ROS_WARN("hex_slam: the coarsest cell is %.3f m and there is no odometry: a robot moving "
             "more than about that between scans may be lost (map_multi_res_levels %d gives "
             "%.3f m)",
             coarsest, levels + 1, 2.0 * coarsest);
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hex_slam::node;
  // Before any thread starts: the scan path's searches reuse what they freed (heap_retention.h).
  const bool retained = hex_slam::RetainFreedMemory();
  ros::init(argc, argv, "hex_slam");
  if (!retained) ROS_WARN("hex_slam: the allocator keeps its own limits on retained memory");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");

  const hex_slam::PrivateParameters params = hex_slam::ReadPrivateParameters(private_nh);
  if (!params.error.empty()) {
    ROS_FATAL("hex_slam: %s", params.error.c_str());
    return 1;
  }
  NodeConfig config;
  const ConfigLoadResult loaded = ApplyNodeConfig(params.values, &config);
  std::vector<std::string> errors = loaded.errors;
  for (const std::string& key : params.non_scalar_keys) {
    errors.push_back("parameter '" + key + "' must be a single value, not a list or dictionary");
  }
  for (const std::string& w : loaded.warnings) ROS_WARN("hex_slam: %s", w.c_str());
  for (const std::string& key : loaded.ignored_keys) {
    ROS_WARN("hex_slam: parameter %s is hector_mapping's and has no effect here", key.c_str());
  }
  if (!errors.empty()) {
    for (const std::string& e : errors) {
      ROS_FATAL("hex_slam: invalid parameter in %s: %s", private_nh.getNamespace().c_str(),
                e.c_str());
    }
    ROS_FATAL("hex_slam: not starting: fix the %zu parameter problem(s) above", errors.size());
    return 1;
  }
  LogMapLevels(config.slam, config.node);

  SlamNode node(nh, private_nh, config);
  const std::string map_error = node.LoadMapFile();
  if (!map_error.empty()) {
    ROS_FATAL("hex_slam: not starting: %s", map_error.c_str());
    return 1;
  }
  node.Start();
  ros::spin();
  // rosconsole is shut down with ros::spin's return: the summary goes to stdout directly.
  const ScanStats stats = node.stats();
  const DropCounters& d = stats.drops;
  std::printf("hex_slam: timing %s\n", stats.timing.Summary().c_str());
  std::printf("hex_slam: dropped scans: queue_overflow=%ld no_laser_transform=%ld invalid=%ld "
              "late=%ld paused=%ld errors=%ld; time_jump_resets=%ld no_odometry=%ld\n",
              d.queue_overflow, d.no_laser_transform, d.invalid, d.late, d.paused, d.errors,
              stats.time_jump_resets, stats.no_odometry);
  std::fflush(stdout);
  return 0;
}
