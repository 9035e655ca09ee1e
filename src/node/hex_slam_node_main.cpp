// hex_slam_node: a drop-in replacement for hector_mapping's node. Reads its private parameters
// once, refuses to start on nonsense values (naming the key), warns about keys it does not know,
// then maps until shut down and logs what the scan callback cost against the bare core.
#include <cstdio>

#include <ros/ros.h>

#include "node_options.h"
#include "rosparam_reader.h"
#include "slam_node.h"

int main(int argc, char** argv) {
  using namespace hex_slam::node;
  ros::init(argc, argv, "hex_slam");
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
  const hex_slam::ParameterTable table = NodeConfigTable(&config);
  for (const std::string& key : params.non_scalar_keys) {
    if (table.Has(key)) {
      errors.push_back("parameter '" + key + "' must be a single value, not a list or dictionary");
    } else {
      ROS_WARN("hex_slam: ignoring unknown parameter %s/%s", private_nh.getNamespace().c_str(),
               key.c_str());
    }
  }
  for (const std::string& key : loaded.unknown_keys) {
    ROS_WARN("hex_slam: ignoring unknown parameter %s/%s (not a hex_slam_node parameter; typo?)",
             private_nh.getNamespace().c_str(), key.c_str());
  }
  for (const std::string& key : loaded.ignored_keys) {
    ROS_WARN("hex_slam: parameter %s is hector_mapping's and has no effect here", key.c_str());
  }
  if (!errors.empty()) {
    for (const std::string& e : errors) ROS_FATAL("hex_slam: invalid parameter: %s", e.c_str());
    ROS_FATAL("hex_slam: not starting: fix the %zu parameter problem(s) above", errors.size());
    return 1;
  }

  SlamNode node(nh, private_nh, config);
  const std::string map_error = node.LoadMapFile();
  if (!map_error.empty()) {
    ROS_FATAL("hex_slam: not starting: %s", map_error.c_str());
    return 1;
  }
  ros::spin();
  // rosconsole is shut down with ros::spin's return: the summary goes to stdout directly.
  const ScanStats stats = node.stats();
  const DropCounters& d = stats.drops;
  std::printf("hex_slam: timing %s\n", stats.timing.Summary().c_str());
  std::printf("hex_slam: dropped scans: no_laser_transform=%ld invalid=%ld late=%ld paused=%ld "
              "errors=%ld; time_jump_resets=%ld no_odometry=%ld\n",
              d.no_laser_transform, d.invalid, d.late, d.paused, d.errors,
              stats.time_jump_resets, stats.no_odometry);
  std::fflush(stdout);
  return 0;
}
