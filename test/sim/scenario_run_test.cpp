#include "hex_slam/sim/scenario_run.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hex_slam {
namespace sim {
namespace {

ScenarioFiles Files() {
  return {std::string(HEX_SLAM_SOURCE_DIR) + "/worlds", DataDirectory(HEX_SLAM_SOURCE_DIR)};
}

Scenario Maze(int beams, int max_scans = 0) {
  Scenario s;
  const std::string error =
      MakeScenario({"maze", 0.01, 0.0, beams}, Files(), ScenarioConditions(), &s);
  if (!error.empty()) ADD_FAILURE() << error;
  if (max_scans > 0 && static_cast<int>(s.truth.size()) > max_scans) s.truth.resize(max_scans);
  return s;
}

TEST(ScenarioRunTest, RecordedDrivesAreDeterministicForASeed) {
  const Scenario s = Maze(360, 50);
  const RecordedDrive a = RecordDrive(s, 4, OdometryNoise::Typical());
  const RecordedDrive b = RecordDrive(s, 4, OdometryNoise::Typical());
  const RecordedDrive c = RecordDrive(s, 5, OdometryNoise::Typical());
  ASSERT_EQ(a.scans.size(), 50u);
  ASSERT_EQ(a.odometry.size(), 50u);
  EXPECT_EQ(a.scans[20].ranges, b.scans[20].ranges);
  EXPECT_NE(a.scans[20].ranges, c.scans[20].ranges);
  EXPECT_EQ(a.odometry[49].x, b.odometry[49].x);
  EXPECT_NE(a.odometry[49].x, c.odometry[49].x);
  EXPECT_DOUBLE_EQ(a.scans[10].stamp, 1.0);
  // Noise-free odometry is the truth itself.
  const RecordedDrive exact = RecordDrive(s, 4);
  EXPECT_NEAR((exact.odometry[49].translation() - exact.truth[49].translation()).norm(), 0.0,
              1e-9);
}

TEST(ScenarioRunTest, CompareTrajectoriesMeasuresKnownErrors) {
  const std::vector<Pose2> truth = {{0, 0, 0}, {1, 0, 0.1}, {2, 0, 3.1}};
  const std::vector<Pose2> estimate = {{0, 0, 0}, {1, 0.3, 0.1}, {2, -0.4, -3.1}};
  const TrajectoryError e = CompareTrajectories(estimate, truth);
  EXPECT_NEAR(e.position_rmse, std::sqrt((0.09 + 0.16) / 3), 1e-12);
  EXPECT_NEAR(e.position_max, 0.4, 1e-12);
  EXPECT_NEAR(e.angle_max, 2 * M_PI - 6.2, 1e-9);  // across the ±pi wrap
  EXPECT_EQ(e.poses, 3);
  EXPECT_THROW(CompareTrajectories({}, truth), std::invalid_argument);
}

// The end-to-end check of the whole pipeline: our maze, 0.01 m² cells, 1000 beams, hex lattice,
// the whole 6-minute drive without odometry. The benchmark measures ~2.5-3 cm here.
TEST(ScenarioRunTest, HexSlamFollowsTheMazeDrive) {
  const Scenario s = Maze(1000);
  const RecordedDrive drive = RecordDrive(s, 1);
  Slam slam(ScenarioSlamOptions(s.spec, "hex"));
  const SlamRun run = RunSlam(drive, false, &slam);
  ASSERT_EQ(run.poses.size(), drive.truth.size());
  EXPECT_GT(run.matched, static_cast<int>(0.99 * drive.truth.size()));
  const TrajectoryError e = CompareTrajectories(run.poses, drive.truth);
  EXPECT_LT(e.position_rmse, 0.05);
  EXPECT_LT(e.position_max, 0.12);
  EXPECT_LT(e.angle_rmse, 0.02);
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
