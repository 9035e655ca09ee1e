#include "hex_slam/logs/offline/offline_config.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "hex_slam/io/parameter_file.h"

namespace hex_slam {
namespace logs {
namespace {

TEST(OfflineConfigTest, SlamAndOfflineKeysApplyRosOnlyKeysAreIgnoredOthersAreErrors) {
  OfflineConfig config;
  std::vector<std::string> ignored;
  const std::vector<std::string> errors = ApplyOfflineParameters(
      {{"map_resolution", "0.1"},
       {"lattice", "square"},
       {"scan_topic", "/base_scan"},
       {"base_frame", "base_footprint"},
       {"use_odometry", "false"},
       {"pub_map_odom_transform", "true"},
       {"map_frame", "map"}},
      &config, &ignored);
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(config.slam.map_resolution, 0.1);
  EXPECT_EQ(config.slam.lattice, "square");
  EXPECT_EQ(config.scan_topic, "/base_scan");
  EXPECT_EQ(config.base_frame, "base_footprint");
  EXPECT_FALSE(config.use_odometry);
  EXPECT_EQ(ignored, (std::vector<std::string>{"map_frame", "pub_map_odom_transform"}));
}

TEST(OfflineConfigTest, UnknownKeysAndBadValuesNameTheKey) {
  OfflineConfig config;
  std::vector<std::string> ignored;
  const std::vector<std::string> errors = ApplyOfflineParameters(
      {{"map_resolutoin", "0.1"}, {"map_size", "big"}}, &config, &ignored);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("map_resolutoin"), std::string::npos);
  EXPECT_NE(errors[1].find("map_size"), std::string::npos);
  EXPECT_TRUE(ignored.empty());
}

TEST(OfflineConfigTest, EveryRosOnlyKeyIsUnknownToTheTable) {
  // A key in both would be silently ignored instead of applied.
  OfflineConfig config;
  const ParameterTable table = OfflineParameterTable(&config);
  for (const std::string& key : RosInterfaceOnlyKeys()) EXPECT_FALSE(table.Has(key)) << key;
}

// Practice 11: every config file the package ships configures an offline run as it is.
TEST(OfflineConfigTest, EveryShippedConfigFileApplies) {
  const std::filesystem::path dir = std::filesystem::path(HEX_SLAM_SOURCE_DIR) / "config";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no config/ folder in this checkout";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    std::map<std::string, std::string> values;
    ASSERT_EQ(io::ReadParameterFile(entry.path().string(), &values), "") << entry.path();
    OfflineConfig config;
    std::vector<std::string> ignored;
    const std::vector<std::string> errors = ApplyOfflineParameters(values, &config, &ignored);
    EXPECT_TRUE(errors.empty()) << entry.path() << ": " << (errors.empty() ? "" : errors.front());
    EXPECT_TRUE(config.slam.Validate().empty()) << entry.path();
  }
  EXPECT_GT(files, 0);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
