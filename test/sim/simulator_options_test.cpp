#include "hex_slam/sim/simulator_options.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace sim {
namespace {

TEST(SimulatorOptionsTest, DefaultsNeedOnlyAWorld) {
  SimulatorOptions options;
  const std::vector<std::string> errors = options.Validate();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("world"), std::string::npos);
  options.world = "worlds/maze.yaml";
  EXPECT_TRUE(options.Validate().empty());
  EXPECT_EQ(options.lidar.beams, 360);
  EXPECT_DOUBLE_EQ(options.rate, 10.0);
}

TEST(SimulatorOptionsTest, TheTableSetsEveryFieldByName) {
  SimulatorOptions options;
  ParameterTable table = SimulatorParameterTable(&options);
  const std::map<std::string, std::string> values = {
      {"world", "w.yaml"}, {"path", "p.yaml"}, {"beams", "1000"}, {"range_noise", "0.02"},
      {"rate", "20"},      {"seed", "7"},      {"laser_x", "0.1"}, {"odom_translation_stddev", "0.05"},
      {"start_yaw", "1.5"}, {"ground_truth_frame", "map"}, {"field_of_view", "4.7"},
      {"real_time_factor", "3"}};
  EXPECT_TRUE(table.Apply(values).empty());
  EXPECT_EQ(options.world, "w.yaml");
  EXPECT_EQ(options.path, "p.yaml");
  EXPECT_EQ(options.lidar.beams, 1000);
  EXPECT_DOUBLE_EQ(options.lidar.range_noise_stddev, 0.02);
  EXPECT_DOUBLE_EQ(options.rate, 20.0);
  EXPECT_EQ(options.seed, 7);
  EXPECT_DOUBLE_EQ(options.laser_mount.x, 0.1);
  EXPECT_DOUBLE_EQ(options.odometry.translation_stddev, 0.05);
  EXPECT_DOUBLE_EQ(options.start.theta, 1.5);
  EXPECT_EQ(options.ground_truth_frame, "map");
  EXPECT_DOUBLE_EQ(options.lidar.field_of_view, 4.7);
  EXPECT_DOUBLE_EQ(options.real_time_factor, 3.0);
  EXPECT_TRUE(options.Validate().empty());
  const std::vector<std::string> errors = table.Apply({{"lidar_beams", "3"}, {"rate", "fast"}});
  ASSERT_EQ(errors.size(), 2u);
}

TEST(SimulatorOptionsTest, ValidateNamesEachBadParameter) {
  SimulatorOptions options;
  options.world = "w.yaml";
  options.rate = 0.0;
  options.lidar.beams = 2;
  options.lidar.range_max = 0.01;
  options.odometry.translation_stddev = -1.0;
  options.laser_frame = "";
  const std::vector<std::string> errors = options.Validate();
  std::string all;
  for (const std::string& e : errors) all += e + "\n";
  EXPECT_EQ(errors.size(), 5u) << all;
  for (const char* key : {"rate", "beams", "range_max", "odom_translation_stddev", "frame"}) {
    EXPECT_NE(all.find(key), std::string::npos) << key;
  }
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
