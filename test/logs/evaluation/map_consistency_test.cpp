#include "hex_slam/logs/evaluation/map_consistency.h"

#include <gtest/gtest.h>

#include "sim_log.h"

namespace hex_slam {
namespace logs {
namespace {

class MapConsistencyTest : public ::testing::Test {
 protected:
  MapConsistencyTest() : drive_(sim::MakeRoomDrive(180)), scans_(test::SimulatedLog(drive_, 7)) {}
  sim::RoomDrive drive_;
  std::vector<LogScan> scans_;
};

TEST_F(MapConsistencyTest, TrueTrajectoryAgreesDoubledWallsDoNot) {
  for (const char* lattice : {"hex", "square"}) {
    SlamOptions options;
    options.lattice = lattice;
    const MapConsistencyReport truth = EvaluateMapConsistency(scans_, drive_.truth, options);
    EXPECT_EQ(truth.agreement.count, static_cast<int>(scans_.size()));
    // The second half of the drive 0.25 m off: every wall it sees is drawn twice.
    std::vector<Pose2> drifted = drive_.truth;
    for (std::size_t i = drifted.size() / 2; i < drifted.size(); ++i) drifted[i].x += 0.25;
    const MapConsistencyReport doubled = EvaluateMapConsistency(scans_, drifted, options);
    // Measured on hex: 0.97 / 0.95 at the truth, 0.86 / 0.71 doubled.
    EXPECT_GT(truth.agreement.mean, 0.93) << lattice;
    EXPECT_GT(truth.low_quantile, 0.9) << lattice;
    EXPECT_LT(doubled.agreement.mean, truth.agreement.mean - 0.07) << lattice;
    EXPECT_LT(doubled.low_quantile, truth.low_quantile - 0.15) << lattice;
  }
}

// A lost run's trajectory, scans scattered over kilometres, is scored (low), never refused: the
// grid grows to its cap and leaves out what lies beyond.
TEST_F(MapConsistencyTest, ATrajectoryThatRanOffIsScoredNotRefused) {
  std::vector<Pose2> lost = drive_.truth;
  for (std::size_t i = lost.size() / 2; i < lost.size(); ++i) {
    lost[i].x += 50.0 * static_cast<double>(i);
    lost[i].y -= 30.0 * static_cast<double>(i);
  }
  SlamOptions options;
  options.map_max_cells = std::int64_t{1} << 22;
  MapConsistencyReport report;
  ASSERT_NO_THROW(report = EvaluateMapConsistency(scans_, lost, options));
  EXPECT_GT(report.agreement.count, 0);
  EXPECT_LT(report.low_quantile, 0.6);
  // The true trajectory scores as before with the storage starting small.
  EXPECT_GT(EvaluateMapConsistency(scans_, drive_.truth, options).agreement.mean, 0.93);
}

TEST_F(MapConsistencyTest, FineCellsStartWithStorageWithinTheCap) {
  // 10 m of 1 mm cells is 10^8 cells, more than map_max_cells: the grid starts smaller (it threw
  // "initial map exceeds the cell cap" and lost hex_slam_offline's outputs).
  SlamOptions options;
  options.map_resolution = 0.001;
  MapConsistencyReport report;
  ASSERT_NO_THROW(report = EvaluateMapConsistency(scans_, drive_.truth, options));
  EXPECT_EQ(report.agreement.count, static_cast<int>(scans_.size()));
}

TEST_F(MapConsistencyTest, UnusableScansAreLeftOut) {
  scans_[3].scan.ranges.clear();
  const MapConsistencyReport r = EvaluateMapConsistency(scans_, drive_.truth, SlamOptions());
  EXPECT_EQ(r.agreement.count, static_cast<int>(scans_.size()) - 1);
  EXPECT_EQ(EvaluateMapConsistency({}, {}, SlamOptions()).agreement.count, 0);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
