#include "hex_slam/sim/scenario.h"

#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "hex_slam/geometry/hex_lattice.h"

namespace hex_slam {
namespace sim {
namespace {

ScenarioFiles Files() {
  return {std::string(HEX_SLAM_SOURCE_DIR) + "/worlds", DataDirectory(HEX_SLAM_SOURCE_DIR)};
}

TEST(ScenarioTest, TheMazeDriveStartsAtTheMapOriginAndStaysInFreeSpace) {
  Scenario s;
  ASSERT_EQ(MakeScenario({"maze", 0.01, 0.0, 360}, Files(), ScenarioConditions(), &s), "");
  ASSERT_GT(s.truth.size(), 1000u);
  EXPECT_NEAR(s.truth.front().translation().norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.truth.front().theta, 0.0, 1e-12);
  EXPECT_NEAR(s.map_frame.x, 0.05, 1e-12);  // the entrance, as stage's start pose
  EXPECT_NEAR(s.map_frame.y, 4.95, 1e-12);
  EXPECT_DOUBLE_EQ(s.scan_period, 0.1);
  EXPECT_EQ(s.lidar.beams, 360);
  // 0.3 m/s at 10 Hz: consecutive poses at most 3 cm apart.
  for (std::size_t i = 1; i < s.truth.size(); ++i) {
    ASSERT_LE((s.truth[i].translation() - s.truth[i - 1].translation()).norm(), 0.03 + 1e-9);
  }
  const PlacedWorld world = s.World();
  for (std::size_t i = 0; i < s.truth.size(); i += 10) {
    ASSERT_FALSE(s.image.IsSolidAt(s.map_frame * s.truth[i].translation())) << i;
    ASSERT_GT(world.CastRay(s.truth[i].translation(), 0.3, 8.0), 0.1) << i;
  }
}

TEST(ScenarioTest, TheStartAngleTurnsTheWorldAgainstTheMapAxes) {
  Scenario s0, s45;
  ASSERT_EQ(MakeScenario({"maze", 0.01, 0.0, 360}, Files(), ScenarioConditions(), &s0), "");
  ASSERT_EQ(MakeScenario({"maze", 0.01, 45.0, 360}, Files(), ScenarioConditions(), &s45), "");
  ASSERT_EQ(s0.truth.size(), s45.truth.size());
  const Pose2 turn(0.0, 0.0, -M_PI / 4);  // the 0° map frame seen from the 45° one
  const PlacedWorld w0 = s0.World(), w45 = s45.World();
  for (std::size_t i = 0; i < s0.truth.size(); i += 97) {
    const Pose2 expected = turn * s0.truth[i];
    EXPECT_NEAR((s45.truth[i].translation() - expected.translation()).norm(), 0.0, 1e-9);
    EXPECT_NEAR(NormalizeAngle(s45.truth[i].theta - expected.theta), 0.0, 1e-9);
    // The same beam in both frames sees the same wall (or the same open entrance).
    const double r45 = w45.CastRay(s45.truth[i].translation(), s45.truth[i].theta + 0.2, 8.0);
    const double r0 = w0.CastRay(s0.truth[i].translation(), s0.truth[i].theta + 0.2, 8.0);
    if (std::isinf(r0)) {
      EXPECT_TRUE(std::isinf(r45)) << i;
    } else {
      EXPECT_NEAR(r45, r0, 1e-9) << i;
    }
  }
  // Walls that ran along the x axis now run at -45° in the map frame: straight up from the
  // start (0°) the top wall is 0.43 m away; at 45° the same wall is found along 45°.
  EXPECT_NEAR(w0.CastRay({0, 0}, M_PI / 2, 8.0), 0.43, 1e-9);
  EXPECT_NEAR(w45.CastRay({0, 0}, M_PI / 4, 8.0), 0.43, 1e-9);
}

TEST(ScenarioTest, EqualCellAreaForBothLattices) {
  for (double area : {0.01, 0.04}) {
    const ScenarioSpec spec{"maze", area, 0.0, 1000};
    const SlamOptions hex = ScenarioSlamOptions(spec, "hex");
    const SlamOptions square = ScenarioSlamOptions(spec, "square");
    EXPECT_EQ(hex.lattice, "hex");
    EXPECT_EQ(square.lattice, "square");
    EXPECT_NEAR(HexLattice(hex.map_resolution).cell_area(), area, 1e-12);
    EXPECT_NEAR(square.map_resolution * square.map_resolution, area, 1e-12);
    EXPECT_TRUE(hex.Validate().empty());
    EXPECT_TRUE(square.Validate().empty());
  }
  EXPECT_NEAR(ScenarioSlamOptions({"maze", 0.01, 0.0, 1000}, "hex").map_resolution, 0.10746,
              1e-5);
}

TEST(ScenarioTest, ThePapersTableHasItsSixRows) {
  const std::vector<PaperRow> rows = PaperTable1();
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0].spec.Name(), "maze/0.01/0/1000");
  EXPECT_EQ(rows[1].spec.Name(), "rooms/0.01/0/1000");
  EXPECT_EQ(rows[5].spec.Name(), "maze/0.01/0/360");
  for (const PaperRow& r : rows) {
    EXPECT_LT(r.hex_position, r.square_position) << r.test;  // the paper's claim, every row
  }
}

TEST(ScenarioTest, MissingWorldsAndUnknownMapsAreErrors) {
  Scenario s;
  EXPECT_NE(MakeScenario({"moon", 0.01, 0.0, 360}, Files(), ScenarioConditions(), &s)
                .find("unknown map"),
            std::string::npos);
  const ScenarioFiles nowhere{"/nonexistent/worlds", "/nonexistent/data"};
  EXPECT_NE(MakeScenario({"maze", 0.01, 0.0, 360}, nowhere, ScenarioConditions(), &s)
                .find("/nonexistent/worlds"),
            std::string::npos);
  EXPECT_NE(MakeScenario({"robotcraft", 0.01, 0.0, 360}, nowhere, ScenarioConditions(), &s)
                .find("/nonexistent/data"),
            std::string::npos);
}

TEST(ScenarioTest, DataDirectoryFollowsTheEnvironment) {
  ::unsetenv("HEX_SLAM_DATA_DIR");
  EXPECT_EQ(DataDirectory("/src/hex_slam"), "/src/hex_slam/../shared/data");
  ::setenv("HEX_SLAM_DATA_DIR", "/data", 1);
  EXPECT_EQ(DataDirectory("/src/hex_slam"), "/data");
  ::unsetenv("HEX_SLAM_DATA_DIR");
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
