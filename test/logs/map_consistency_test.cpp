#include "hex_slam/logs/map_consistency.h"

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

TEST_F(MapConsistencyTest, UnusableScansAreLeftOut) {
  scans_[3].scan.ranges.clear();
  const MapConsistencyReport r = EvaluateMapConsistency(scans_, drive_.truth, SlamOptions());
  EXPECT_EQ(r.agreement.count, static_cast<int>(scans_.size()) - 1);
  EXPECT_EQ(EvaluateMapConsistency({}, {}, SlamOptions()).agreement.count, 0);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
