#include "node_options.h"

#include <algorithm>

namespace hex_slam {
namespace node {
namespace {

// The parameters that name tf frames.
constexpr std::array<const char*, 4> kFrameKeys = {"base_frame", "map_frame", "odom_frame",
                                                   "tf_map_scanmatch_transform_frame_name"};

// tf2 frame ids: non-empty, no leading slash (tf2 rejects "/map"), no spaces.
bool IsFrameId(const std::string& frame) {
  return !frame.empty() && frame[0] != '/' && frame.find(' ') == std::string::npos;
}

}  // namespace

std::vector<std::string> NodeOptions::Validate() const {
  std::vector<std::string> errors;
  auto require = [&errors](bool ok, const std::string& message) {
    if (!ok) errors.push_back(message);
  };
  auto require_frame = [&require](const char* key, const std::string& frame) {
    require(IsFrameId(frame), std::string(key) + " must be a frame id (non-empty, no leading " +
                                  "'/', no spaces), got '" + frame + "'");
  };
  require_frame("base_frame", base_frame);
  require_frame("map_frame", map_frame);
  require_frame("odom_frame", odom_frame);
  require_frame("tf_map_scanmatch_transform_frame_name", tf_map_scanmatch_transform_frame_name);
  require(map_frame != base_frame, "map_frame and base_frame must differ");
  require(map_frame != odom_frame, "map_frame and odom_frame must differ");
  require(!scan_topic.empty(), "scan_topic must not be empty");
  require(!sys_msg_topic.empty(), "sys_msg_topic must not be empty");
  require(!pose_update_topic.empty(), "pose_update_topic must not be empty");
  require(scan_subscriber_queue_size >= 1, "scan_subscriber_queue_size must be >= 1");
  require(tf_timeout >= 0.0 && tf_timeout <= 10.0, "tf_timeout must lie in [0, 10] s");
  require(map_pub_period > 0.0, "map_pub_period must be > 0");
  require(hex_map_pub_period >= 0.0, "hex_map_pub_period must be >= 0 (0 disables)");
  require(hex_map_max_cells >= 1, "hex_map_max_cells must be >= 1");
  require(hex_map_level >= 0, "hex_map_level must be >= 0");
  require(map_pub_resolution >= 0.0, "map_pub_resolution must be >= 0 (0: map_resolution)");
  require(trajectory_min_distance >= 0.0, "trajectory_min_distance must be >= 0");
  require(trajectory_min_angle >= 0.0, "trajectory_min_angle must be >= 0");
  require(trajectory_max_poses >= 2, "trajectory_max_poses must be >= 2");
  require(!map_file_base.empty(), "map_file_base must not be empty");
  require(time_jump_reset_threshold > 0.0, "time_jump_reset_threshold must be > 0");
  for (const std::string& e : planner.Validate()) errors.push_back(e);
  return errors;
}

std::vector<std::string> NodeConfig::Validate() const {
  std::vector<std::string> errors = slam.Validate();
  for (const std::string& e : node.Validate()) errors.push_back(e);
  return errors;
}

ParameterTable NodeParameterTable(NodeOptions* o) {
  ParameterTable t;
  t.Add("base_frame", &o->base_frame, "the robot's frame, whose pose is estimated");
  t.Add("map_frame", &o->map_frame, "the map's frame");
  t.Add("odom_frame", &o->odom_frame, "odometry frame; equal to base_frame when there is none");
  t.Add("scan_topic", &o->scan_topic, "sensor_msgs/LaserScan input");
  t.Add("sys_msg_topic", &o->sys_msg_topic, "std_msgs/String commands (\"reset\")");
  t.Add("pose_update_topic", &o->pose_update_topic, "PoseWithCovarianceStamped output");
  t.Add("scan_subscriber_queue_size", &o->scan_subscriber_queue_size, "scan queue length");
  t.Add("pub_map_odom_transform", &o->pub_map_odom_transform,
        "publish tf map->odom (map->base when odom_frame == base_frame)");
  t.Add("pub_map_scanmatch_transform", &o->pub_map_scanmatch_transform,
        "publish tf map->tf_map_scanmatch_transform_frame_name at the estimated pose");
  t.Add("tf_map_scanmatch_transform_frame_name", &o->tf_map_scanmatch_transform_frame_name,
        "frame name of the estimated pose");
  t.Add("pub_odometry", &o->pub_odometry, "publish nav_msgs/Odometry on scanmatch_odom");
  t.Add("use_tf_scan_transformation", &o->use_tf_scan_transformation,
        "look the laser's mount up in tf (false: laser at the base origin)");
  t.Add("use_tf_pose_start_estimate", &o->use_tf_pose_start_estimate,
        "start each match from tf map->base_frame");
  t.Add("use_odometry", &o->use_odometry,
        "seed the matcher with odom->base_frame motion (needs odom_frame != base_frame)");
  t.Add("tf_timeout", &o->tf_timeout, "longest wait for odometry at a scan's stamp (s)");
  t.Add("map_pub_period", &o->map_pub_period, "map and map_metadata publishing period (s)");
  t.Add("advertise_map_service", &o->advertise_map_service, "offer the dynamic_map service");
  t.Add("hex_map_pub_period", &o->hex_map_pub_period,
        "hex_map marker publishing period (s), 0 disables");
  t.Add("hex_map_max_cells", &o->hex_map_max_cells, "most cells drawn in the hex_map marker");
  t.Add("hex_map_level", &o->hex_map_level,
        "pyramid level the hex_map marker draws (0: the finest; clamped to the levels)");
  t.Add("map_pub_resolution", &o->map_pub_resolution,
        "/map pixel size in m (0: map_resolution)");
  t.Add("trajectory_min_distance", &o->trajectory_min_distance,
        "trajectory keeps a pose after this much travel (m)");
  t.Add("trajectory_min_angle", &o->trajectory_min_angle,
        "trajectory keeps a pose after this much turning (rad)");
  t.Add("trajectory_max_poses", &o->trajectory_max_poses,
        "trajectory thins itself to half past this many poses");
  t.Add("map_file_base", &o->map_file_base,
        "save_map writes <base>.pgm, <base>.yaml and <base>.hexmap");
  t.Add("map_file", &o->map_file,
        "a .hexmap to start from and to reload on reset (localization with update_map false)");
  t.Add("planner_robot_radius", &o->planner.robot_radius,
        "plan_path keeps cell centres this far from obstacles' (m)");
  t.Add("planner_occupied_probability", &o->planner.occupied_probability,
        "plan_path treats cells at or above this occupancy as obstacles");
  t.Add("planner_allow_unknown", &o->planner.allow_unknown,
        "plan_path may cross cells never observed");
  t.Add("planner_keep_clear_of_unknown", &o->planner.keep_clear_of_unknown,
        "plan_path keeps planner_robot_radius from the edge of the unexplored too");
  t.Add("plan_on_goal", &o->plan_on_goal,
        "plan to each move_base_simple/goal (rviz's 2D Nav Goal) onto planned_path");
  t.Add("time_jump_reset_threshold", &o->time_jump_reset_threshold,
        "a scan this much older than the last resets the map; less is dropped (s)");
  t.Add("output_timing", &o->output_timing, "log each scan callback's duration");
  return t;
}

ParameterTable NodeConfigTable(NodeConfig* config) {
  ParameterTable t = SlamParameterTable(&config->slam);
  t.Merge(NodeParameterTable(&config->node));
  IgnoredHectorOptions& ignored = config->ignored;
  const std::string no_effect = "hector_mapping parameter, accepted with no effect";
  t.Add("pub_drawings", &ignored.pub_drawings, no_effect);
  t.Add("pub_debug_output", &ignored.pub_debug_output, no_effect);
  return t;
}

ConfigLoadResult ApplyNodeConfig(const std::map<std::string, std::string>& values,
                                 NodeConfig* config) {
  ConfigLoadResult result;
  ParameterTable table = NodeConfigTable(config);
  for (const auto& [key, text] : values) {
    if (!table.Has(key)) {
      result.errors.push_back(table.UnknownKeyMessage(key));
      continue;
    }
    if (std::find(kIgnoredHectorKeys.begin(), kIgnoredHectorKeys.end(), key) !=
        kIgnoredHectorKeys.end()) {
      result.ignored_keys.push_back(key);
    }
    std::string value = text;
    const std::size_t name_start = value.find_first_not_of('/');
    if (std::find(kFrameKeys.begin(), kFrameKeys.end(), key) != kFrameKeys.end() &&
        name_start != 0 && name_start != std::string::npos) {
      // tf1-era launch files write "/base_link"; tf2 frame ids have no leading slash.
      value = value.substr(name_start);
      result.warnings.push_back(key + " '" + text + "' read as '" + value +
                                "' (tf2 frame ids have no leading '/')");
    }
    const std::string error = table.Set(key, value);
    if (!error.empty()) result.errors.push_back(error);
  }
  for (const std::string& e : config->Validate()) result.errors.push_back(e);
  return result;
}

}  // namespace node
}  // namespace hex_slam
