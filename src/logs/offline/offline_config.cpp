#include "hex_slam/logs/offline/offline_config.h"

#include <algorithm>

namespace hex_slam {
namespace logs {
namespace {

// Two: the worker can take the next finished submap while the front end fills one more.
constexpr int kOfflineMaxQueuedSubmaps = 2;

}  // namespace

void UseOfflineDefaults(SlamOptions* options) {
  options->loop_closure.live_map = false;
  options->loop_closure.worker_niceness = 0;
  options->loop_closure.max_queued_submaps = kOfflineMaxQueuedSubmaps;
}

std::vector<std::string> RosInterfaceOnlyKeys() {
  return {
      // hector_mapping's
      "advertise_map_service", "map_frame",
      "map_pub_period", "output_timing", "pose_update_topic", "pub_debug_output", "pub_drawings",
      "pub_map_odom_transform", "pub_map_scanmatch_transform", "pub_odometry",
      "scan_subscriber_queue_size", "sys_msg_topic", "tf_map_scanmatch_transform_frame_name",
      "use_tf_pose_start_estimate", "use_tf_scan_transformation",
      // hex_slam_node's own: publishing, saving, tf waits, bag restarts
      "hex_map_level", "hex_map_max_cells", "hex_map_pub_period", "map_file_base",
      "map_pub_resolution", "tf_timeout", "time_jump_reset_threshold"};
}

ParameterTable OfflineParameterTable(OfflineConfig* config) {
  ParameterTable t = SlamParameterTable(&config->slam);
  t.Add("scan_topic", &config->scan_topic, "bag topic of the sensor_msgs/LaserScan messages");
  t.Add("base_frame", &config->base_frame, "the robot's frame in the bag's tf");
  t.Add("odom_frame", &config->odom_frame, "the odometry frame in the bag's tf");
  t.Add("use_odometry", &config->use_odometry, "use the log's odometry as the motion prior");
  return t;
}

std::vector<std::string> ApplyOfflineParameters(const std::map<std::string, std::string>& values,
                                                OfflineConfig* config,
                                                std::vector<std::string>* ignored) {
  ParameterTable table = OfflineParameterTable(config);
  const std::vector<std::string> ros_only = RosInterfaceOnlyKeys();
  std::map<std::string, std::string> used;
  for (const auto& [key, value] : values) {
    if (!table.Has(key) && std::find(ros_only.begin(), ros_only.end(), key) != ros_only.end()) {
      ignored->push_back(key);
    } else {
      used[key] = value;
    }
  }
  return table.Apply(used);
}

}  // namespace logs
}  // namespace hex_slam
