// What hex_slam_node reads at start-up besides the core's SlamOptions: frames, topics, tf, output
// periods, files. hector_mapping's names and defaults wherever the concept is the same, so a
// hector launch file works unchanged. ROS-free: the same table loads rosparams and YAML files.
#ifndef HEX_SLAM_NODE_NODE_OPTIONS_H_
#define HEX_SLAM_NODE_NODE_OPTIONS_H_

#include <array>
#include <map>
#include <string>
#include <vector>

#include "hex_slam/planning/hex_planner.h"
#include "hex_slam/common/parameter_table.h"
#include "hex_slam/mapping/slam_options.h"

namespace hex_slam {
namespace node {

struct NodeOptions {
  // Frames (hector_mapping).
  std::string base_frame = "base_link";
  std::string map_frame = "map";
  std::string odom_frame = "odom";  // equal to base_frame: no odometry, map->base is published

  // Topics (hector_mapping).
  std::string scan_topic = "scan";
  std::string sys_msg_topic = "syscommand";
  std::string pose_update_topic = "poseupdate";
  int scan_subscriber_queue_size = 5;

  // tf and pose output (hector_mapping).
  bool pub_map_odom_transform = true;
  bool pub_map_scanmatch_transform = true;
  std::string tf_map_scanmatch_transform_frame_name = "scanmatcher_frame";
  bool pub_odometry = false;  // nav_msgs/Odometry on scanmatch_odom

  // tf input. hector_mapping's two flags, plus the odometry prior hector lacks: odom->base at the
  // scan's stamp seeds the matcher with the motion since the previous scan.
  bool use_tf_scan_transformation = true;  // false: the laser sits at the base origin
  // Start each match from tf map->base at the scan's stamp, when something else publishes it
  // (never waited for; without it the previous estimate is used).
  bool use_tf_pose_start_estimate = false;
  bool use_odometry = true;  // only when odom_frame != base_frame
  // How long a scan's callback may wait for odom->base at the scan's stamp (odometry often
  // arrives a few ms after the scan). The laser mount is never waited for: it is looked up once.
  double tf_timeout = 0.1;  // s

  // Map output (hector_mapping's map_pub_period and advertise_map_service).
  double map_pub_period = 2.0;  // s
  bool advertise_map_service = true;
  // /map's pixel (m): the hex cells resampled onto squares of this side. 0: map_resolution, the
  // pixel hector_mapping's users expect.
  double map_pub_resolution = 0.0;
  // The hexagon marker: cheap only when small and slow; never built without a subscriber.
  double hex_map_pub_period = 5.0;  // s; 0 disables
  int hex_map_max_cells = 200000;   // more known cells than this: the marker shows the first ones
  // The pyramid level the marker draws: 1 (cells of twice map_resolution, a quarter as many as
  // the finest) shows as hexagons at the shipped rviz view's zoom; 0 draws the finest.
  int hex_map_level = 1;
  // The published trajectory keeps a pose every trajectory_min_distance m or
  // trajectory_min_angle rad, and halves itself (every other pose) past trajectory_max_poses.
  double trajectory_min_distance = 0.05;
  double trajectory_min_angle = 0.05;
  int trajectory_max_poses = 20000;
  // save_map writes <map_file_base>.pgm/.yaml (map_server) and <map_file_base>.hexmap; relative
  // paths are relative to the node's working directory (ROS_HOME under roslaunch).
  std::string map_file_base = "hex_slam_map";
  // A .hexmap (save_map's, or hex_slam_offline's map.hexmap) to start from, and to return to on
  // every reset. With update_map false the node localizes on it without changing it.
  std::string map_file;

  // plan_path (nav_msgs/GetPlan): shortest paths on the hex map, published on planned_path.
  HexPlannerOptions planner;
  bool plan_on_goal = true;  // plan to each goal on move_base_simple/goal (rviz's 2D Nav Goal)

  // A scan stamped more than this before the previous one means the source restarted (a bag
  // played again, a simulator reset): the map is reset. Smaller steps back are dropped.
  double time_jump_reset_threshold = 1.0;  // s

  bool output_timing = false;  // hector_mapping: log every callback's duration

  // Empty when valid; otherwise one message per bad field, naming its parameter.
  std::vector<std::string> Validate() const;
};

// hector_mapping parameters accepted so its launch files load, but with no effect here: the
// loader warns when one is set.
inline constexpr std::array<const char*, 2> kIgnoredHectorKeys = {"pub_drawings",
                                                                  "pub_debug_output"};

// Their fields: the drawings and debug output are hector's internals.
struct IgnoredHectorOptions {
  bool pub_drawings = false;
  bool pub_debug_output = false;
};

// The node's whole configuration, under one parameter table.
struct NodeConfig {
  // With loop closure the node publishes a map it draws from the nodes on its map thread
  // (RedrawnMap), never Slam's global map: keeping that one live would cost the scan callback a
  // second map insertion per inserted scan for nothing (loop_closure_live_map may still be set).
  NodeConfig() { slam.loop_closure.live_map = false; }

  SlamOptions slam;
  NodeOptions node;
  IgnoredHectorOptions ignored;

  // The core's and the node's problems together.
  std::vector<std::string> Validate() const;
};

ParameterTable NodeParameterTable(NodeOptions* options);
// SlamParameterTable, NodeParameterTable and the ignored hector keys, merged.
ParameterTable NodeConfigTable(NodeConfig* config);

struct ConfigLoadResult {
  // Unknown keys (with the nearest known one), unparsable values and failed validation: fatal.
  std::vector<std::string> errors;
  std::vector<std::string> ignored_keys;  // hector parameters with no effect here: warn
  std::vector<std::string> warnings;      // values accepted after a fix (a frame's leading '/')
  bool ok() const { return errors.empty(); }
};

// Applies `values` (key -> text) over `config`'s current values, then validates the result.
ConfigLoadResult ApplyNodeConfig(const std::map<std::string, std::string>& values,
                                 NodeConfig* config);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_NODE_OPTIONS_H_
