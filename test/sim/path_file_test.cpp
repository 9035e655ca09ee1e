#include "hex_slam/sim/path_file.h"

#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "hex_slam/sim/image_world.h"
#include "hex_slam/sim/scenario.h"

namespace hex_slam {
namespace sim {
namespace {

std::string TempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/hex_slam_path_test_" + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

const char* const kHeader = "format: hex_slam_waypoint_path\nversion: 1\n";

TEST(PathFileTest, RoundTrip) {
  WaypointPath path;
  path.start_heading = 0.25;
  path.waypoints = {{0.05, 4.95}, {0.45, 4.95}, {-1.0 / 3.0, 2.0}};
  const std::string file = ::testing::TempDir() + "/hex_slam_path_roundtrip.yaml";
  ASSERT_EQ(WriteWaypointPath(file, path), "");
  WaypointPath read;
  ASSERT_EQ(ReadWaypointPath(file, &read), "");
  EXPECT_DOUBLE_EQ(read.start_heading, 0.25);
  ASSERT_EQ(read.waypoints.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR((read.waypoints[i] - path.waypoints[i]).norm(), 0, 1e-9);
  std::remove(file.c_str());
}

TEST(PathFileTest, BadFilesGiveErrorsAndLeaveTheOutputAlone) {
  const std::string good = std::string(kHeader) + "waypoints:\n  - [1, 2]\n";
  const struct {
    const char* name;
    std::string text;
    const char* expect;
  } cases[] = {
      {"unknown_key", good + "speed: 3\n", "unknown key 'speed'"},
      {"no_format", "version: 1\nwaypoints:\n  - [1, 2]\n", "format"},
      {"version", "format: hex_slam_waypoint_path\nversion: 2\nwaypoints:\n  - [1, 2]\n",
       "version"},
      {"empty", std::string(kHeader) + "waypoints: []\n", "non-empty"},
      {"not_pair", std::string(kHeader) + "waypoints:\n  - [1, 2, 3]\n", "waypoint 0"},
      {"not_number", std::string(kHeader) + "waypoints:\n  - [1, 2]\n  - [a, 2]\n",
       "waypoint 1"},
      {"not_finite", std::string(kHeader) + "waypoints:\n  - [.nan, 2]\n", "not finite"},
      {"heading", std::string(kHeader) + "start_heading: north\nwaypoints:\n  - [1, 2]\n",
       "bad value"},
      {"not_yaml", "waypoints: [[1, 2]\n", ""},
      {"not_mapping", "- 1\n- 2\n", "mapping"},
  };
  for (const auto& c : cases) {
    WaypointPath out;
    out.start_heading = 9.0;
    const std::string file = TempFile(c.name, c.text);
    const std::string error = ReadWaypointPath(file, &out);
    EXPECT_FALSE(error.empty()) << c.name;
    EXPECT_NE(error.find(c.expect), std::string::npos) << c.name << ": " << error;
    EXPECT_NE(error.find(file), std::string::npos) << c.name << ": " << error;
    EXPECT_EQ(out.start_heading, 9.0) << c.name;
    std::remove(file.c_str());
  }
  WaypointPath out;
  EXPECT_FALSE(ReadWaypointPath("/nonexistent/path.yaml", &out).empty());
  EXPECT_FALSE(WriteWaypointPath(::testing::TempDir() + "/x.yaml", WaypointPath()).empty());
}

// Every shipped path (and the robotcraft one) stays in free space, away from the walls.
TEST(PathFileTest, ShippedPathsKeepClearOfTheWalls) {
  const std::string worlds = std::string(HEX_SLAM_SOURCE_DIR) + "/worlds";
  const struct {
    std::string world, path;
    bool bitmap;
  } shipped[] = {
      {worlds + "/maze.yaml", worlds + "/maze_path.yaml", false},
      {worlds + "/rooms.yaml", worlds + "/rooms_path.yaml", false},
      {DataDirectory(HEX_SLAM_SOURCE_DIR) + "/robotcraft_maze/540x540-90cm.png",
       worlds + "/robotcraft_maze_path.yaml", true},
  };
  const double clearance = 0.1;  // make_worlds.py keeps 0.15 m
  for (const auto& s : shipped) {
    ImageWorld world;
    if (s.bitmap && !std::ifstream(s.world)) continue;  // the paper's maze is optional
    ASSERT_EQ(s.bitmap ? LoadBitmapWorld(s.world, 0.01, {0, 0}, &world)
                       : LoadImageWorld(s.world, ImageWorldOptions(), &world),
              "");
    WaypointPath path;
    ASSERT_EQ(ReadWaypointPath(s.path, &path), "");
    ASSERT_GE(path.waypoints.size(), 10u) << s.path;
    for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
      const Eigen::Vector2d a = path.waypoints[i], b = path.waypoints[i + 1];
      for (double t = 0.0; t <= 1.0; t += 0.01) {
        const Eigen::Vector2d p = a + t * (b - a);
        for (int k = 0; k < 16; ++k) {
          ASSERT_TRUE(std::isinf(world.CastRay(p, k * M_PI / 8, clearance)))
              << s.path << ": segment " << i << " at " << p.transpose();
        }
      }
    }
  }
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
