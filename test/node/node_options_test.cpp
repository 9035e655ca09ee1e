#include "node_options.h"

#include <dirent.h>

#include <algorithm>

#include <gtest/gtest.h>

#include "hex_slam/io/parameter_file.h"

namespace hex_slam {
namespace node {
namespace {

std::string Joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const std::string& line : lines) all += line + "\n";
  return all;
}

TEST(NodeOptionsTest, DefaultsAreValidAndHectors) {
  const NodeConfig config;
  EXPECT_EQ(Joined(config.Validate()), "");
  // hector_mapping's defaults (HectorMappingRos.cpp), where the concept is the same.
  const NodeOptions& o = config.node;
  EXPECT_EQ(o.base_frame, "base_link");
  EXPECT_EQ(o.map_frame, "map");
  EXPECT_EQ(o.odom_frame, "odom");
  EXPECT_EQ(o.scan_topic, "scan");
  EXPECT_EQ(o.sys_msg_topic, "syscommand");
  EXPECT_EQ(o.pose_update_topic, "poseupdate");
  EXPECT_EQ(o.scan_subscriber_queue_size, 5);
  EXPECT_TRUE(o.pub_map_odom_transform);
  EXPECT_TRUE(o.pub_map_scanmatch_transform);
  EXPECT_EQ(o.tf_map_scanmatch_transform_frame_name, "scanmatcher_frame");
  EXPECT_FALSE(o.pub_odometry);
  EXPECT_TRUE(o.use_tf_scan_transformation);
  EXPECT_FALSE(o.use_tf_pose_start_estimate);
  EXPECT_DOUBLE_EQ(o.map_pub_period, 2.0);
  EXPECT_TRUE(o.advertise_map_service);
  EXPECT_FALSE(o.output_timing);
  EXPECT_EQ(config.slam.map_multi_res_levels, 3);
  // The node draws its published map from the nodes; Slam's global map is not kept live.
  EXPECT_TRUE(config.slam.loop_closure.enabled);
  EXPECT_FALSE(config.slam.loop_closure.live_map);
}

TEST(NodeOptionsTest, EveryHectorMappingParameterIsAccepted) {
  // The private parameters hector_mapping reads, each with a value of the right type.
  const std::map<std::string, std::string> hector = {
      {"pub_drawings", "false"}, {"pub_debug_output", "false"},
      {"pub_map_odom_transform", "true"}, {"pub_odometry", "true"},
      {"advertise_map_service", "true"}, {"scan_subscriber_queue_size", "5"},
      {"map_resolution", "0.025"}, {"map_size", "2048"}, {"map_start_x", "0.5"},
      {"map_start_y", "0.5"}, {"map_multi_res_levels", "2"}, {"update_factor_free", "0.4"},
      {"update_factor_occupied", "0.9"}, {"map_update_distance_thresh", "0.4"},
      {"map_update_angle_thresh", "0.06"}, {"scan_topic", "scan"},
      {"sys_msg_topic", "syscommand"}, {"pose_update_topic", "poseupdate"},
      {"use_tf_scan_transformation", "true"}, {"use_tf_pose_start_estimate", "false"},
      {"map_with_known_poses", "false"}, {"base_frame", "base_footprint"},
      {"map_frame", "map"}, {"odom_frame", "odom"}, {"pub_map_scanmatch_transform", "true"},
      {"tf_map_scanmatch_transform_frame_name", "scanmatcher_frame"},
      {"output_timing", "false"}, {"map_pub_period", "2.0"}, {"laser_min_dist", "0.4"},
      {"laser_max_dist", "30.0"}, {"laser_z_min_value", "-1.0"}, {"laser_z_max_value", "1.0"}};
  NodeConfig config;
  const ConfigLoadResult result = ApplyNodeConfig(hector, &config);
  EXPECT_EQ(Joined(result.errors), "");
  // The two with no effect here (hector's debug drawings) are named so the user is told.
  std::vector<std::string> ignored = result.ignored_keys;
  std::sort(ignored.begin(), ignored.end());
  EXPECT_EQ(ignored, (std::vector<std::string>{"pub_debug_output", "pub_drawings"}));
  EXPECT_DOUBLE_EQ(config.slam.laser_z_min_value, -1.0);
  EXPECT_EQ(config.node.base_frame, "base_footprint");
  EXPECT_DOUBLE_EQ(config.slam.map_resolution, 0.025);
  EXPECT_EQ(config.slam.map_multi_res_levels, 2);
  EXPECT_TRUE(config.node.pub_odometry);
}

TEST(NodeOptionsTest, NonsenseValuesAreErrorsNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"map_resolution", "-0.05"}, {"map_multi_res_levels", "0"}, {"lattice", "triangle"},
      {"map_resolution", "fine"},  {"base_frame", ""},            {"map_frame", "/"},
      {"laser_z_min_value", "2.0"}, {"hex_map_level", "-1"},  {"map_pub_resolution", "-1"},
      {"scan_subscriber_queue_size", "0"}, {"map_pub_period", "0"}, {"tf_timeout", "-1"},
      {"time_jump_reset_threshold", "0"}, {"hex_map_pub_period", "-2"},
      {"trajectory_max_poses", "1"}, {"use_odometry", "perhaps"}, {"map_file_base", ""}};
  for (const auto& [key, value] : bad) {
    NodeConfig config;
    const ConfigLoadResult result = ApplyNodeConfig({{key, value}}, &config);
    EXPECT_FALSE(result.ok()) << key << " = '" << value << "' was accepted";
    EXPECT_NE(Joined(result.errors).find(key), std::string::npos)
        << key << " = '" << value << "': " << Joined(result.errors);
  }
  NodeConfig config;
  EXPECT_FALSE(ApplyNodeConfig({{"map_frame", "base_link"}}, &config).ok());
}

TEST(NodeOptionsTest, UnknownKeysAreFatalWithTheNearestKnownOne) {
  NodeConfig config;
  const ConfigLoadResult result =
      ApplyNodeConfig({{"map_resoluton", "0.05"}, {"map_size", "512"}}, &config);
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(Joined(result.errors),
            "unknown parameter 'map_resoluton' (did you mean 'map_resolution'?)\n");
  EXPECT_EQ(config.slam.map_size, 512);
  // Nothing near: no suggestion.
  const ConfigLoadResult far = ApplyNodeConfig({{"colour_scheme", "dark"}}, &config);
  EXPECT_EQ(Joined(far.errors), "unknown parameter 'colour_scheme'\n");
}

TEST(NodeOptionsTest, FrameIdsLoseALeadingSlashWithAWarning) {
  NodeConfig config;
  const ConfigLoadResult result = ApplyNodeConfig(
      {{"base_frame", "/base_link"}, {"odom_frame", "//odom"}, {"map_frame", "map"}}, &config);
  EXPECT_TRUE(result.ok()) << Joined(result.errors);
  EXPECT_EQ(config.node.base_frame, "base_link");
  EXPECT_EQ(config.node.odom_frame, "odom");
  EXPECT_EQ(result.warnings.size(), 2u);
  EXPECT_NE(Joined(result.warnings).find("base_frame '/base_link' read as 'base_link'"),
            std::string::npos);
}

TEST(NodeOptionsTest, NodeAndCoreKeysDoNotCollide) {
  NodeConfig config;
  // Merge throws on a key registered twice.
  EXPECT_NO_THROW(NodeConfigTable(&config));
  EXPECT_TRUE(NodeConfigTable(&config).Has("lattice"));
  EXPECT_TRUE(NodeConfigTable(&config).Has("use_odometry"));
}

// Practice 11: every shipped config file loads through the node's table and validates.
std::vector<std::string> ConfigFiles() {
  std::vector<std::string> files;
  if (DIR* dir = ::opendir(HEX_SLAM_CONFIG_DIR)) {
    while (dirent* entry = ::readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
        files.push_back(std::string(HEX_SLAM_CONFIG_DIR) + "/" + name);
      }
    }
    ::closedir(dir);
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ShippedConfigTest, EveryConfigFileLoadsAndValidates) {
  const std::vector<std::string> files = ConfigFiles();
  ASSERT_GE(files.size(), 3u) << "expected default, rosbot_rplidar and mit_stata in "
                              << HEX_SLAM_CONFIG_DIR;
  for (const std::string& file : files) {
    std::map<std::string, std::string> values;
    ASSERT_EQ(io::ReadParameterFile(file, &values), "") << file;
    EXPECT_FALSE(values.empty()) << file;
    NodeConfig config;
    const ConfigLoadResult result = ApplyNodeConfig(values, &config);
    EXPECT_EQ(Joined(result.errors), "") << file;
    EXPECT_TRUE(result.ignored_keys.empty()) << file << " sets keys with no effect";
  }
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
