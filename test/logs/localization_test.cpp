// Localization on a saved map: a drive mapped, the map saved to a .hexmap file and loaded into a
// fresh Slam with update_map false, the drive driven again with other noise from a wrong start.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "../io/temp_dir.h"
#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace {

SlamOptions RoomOptions(const std::string& lattice) {
  SlamOptions options;
  options.lattice = lattice;
  options.map_resolution = 0.05;
  options.map_size = 256;
  return options;
}

struct DriveRun {
  double position_rmse = 0.0;
  double position_max = 0.0;  // over all scans but the first, which starts from the wrong pose
  int matched = 0;
  int map_updates = 0;
  int initialized = 0;
};

DriveRun Drive(const sim::RoomDrive& drive, unsigned seed, Slam* slam) {
  std::mt19937_64 rng(seed);
  DriveRun run;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    const LaserScan scan =
        sim::SimulateScan(drive.world, drive.truth[i], drive.lidar, drive.scan_period * i, &rng);
    const ScanReport report = slam->ProcessScan(scan);
    run.matched += report.outcome == ScanOutcome::kMatched;
    run.initialized += report.outcome == ScanOutcome::kInitialized;
    run.map_updates += report.map_updated;
    const double e = (report.pose.translation() - drive.truth[i].translation()).norm();
    sum_sq += e * e;
    if (i > 0) run.position_max = std::max(run.position_max, e);
  }
  run.position_rmse = std::sqrt(sum_sq / drive.truth.size());
  return run;
}

// Bounds as the mapping drive's (test/core/mapping/slam_test.cpp): 2 cm RMSE, 5 cm on any scan; the map
// is the mapping run's, so localizing on it cannot be much better than mapping was.
constexpr double kRmseBound = 0.02;
constexpr double kMaxBound = 0.05;

class LocalizationTest : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Lattices, LocalizationTest, ::testing::Values("hex", "square"));

TEST_P(LocalizationTest, ASavedMapLocalizesAnotherDriveAndStaysAsSaved) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(360);
  SlamOptions mapping_options = RoomOptions(GetParam());
  mapping_options.loop_closure.enabled = true;  // so the saved map carries a graph
  Slam mapping(mapping_options);
  mapping.Reset(drive.truth.front());
  const DriveRun mapped = Drive(drive, 1, &mapping);
  ASSERT_GT(mapped.map_updates, 5);
  mapping.FinishTrajectory();  // with loop closure: the map drawn at the optimised poses

  testing_util::TempDir dir;
  const std::string path = dir.File("room.hexmap");
  const io::HexMapData saved = io::CaptureSlamMap(mapping);
  ASSERT_EQ(io::WriteHexMapFile(path, saved), "");
  // Version 3: the loop-closure graph goes with the map, and comes back.
  ASSERT_EQ(saved.graph.nodes.size(), mapping.Nodes().size());
  ASSERT_FALSE(saved.graph.submaps.empty());
  io::HexMapData reread;
  ASSERT_EQ(io::ReadHexMapFile(path, &reread), "");
  ASSERT_EQ(reread.graph.nodes.size(), saved.graph.nodes.size());
  ASSERT_EQ(reread.graph.constraints.size(), saved.graph.constraints.size());
  for (std::size_t i = 0; i < saved.graph.nodes.size(); ++i) {
    EXPECT_EQ(reread.graph.nodes[i].global_pose.x, saved.graph.nodes[i].global_pose.x);
    EXPECT_EQ(reread.graph.nodes[i].points, saved.graph.nodes[i].points);
  }

  SlamOptions options = RoomOptions(GetParam());
  options.update_map = false;
  Slam localizing(options);
  // Started 10 cm and 3° off, as a user's rough initial pose would be.
  const Pose2& start = drive.truth.front();
  localizing.SetPose(Pose2(start.x + 0.08, start.y - 0.06, start.theta + 0.05));
  ASSERT_EQ(io::LoadSlamMap(path, &localizing), "");
  const DriveRun localized = Drive(drive, 2, &localizing);

  EXPECT_EQ(localized.initialized, 0) << "the loaded map was replaced by the first scan";
  EXPECT_EQ(localized.matched, static_cast<int>(drive.truth.size()));
  EXPECT_EQ(localized.map_updates, 0);
  EXPECT_LT(localized.position_rmse, kRmseBound);
  EXPECT_LT(localized.position_max, kMaxBound);
  std::cout << GetParam() << ": mapping RMSE " << mapped.position_rmse << " m; localizing on the "
            << "saved map RMSE " << localized.position_rmse << " m, worst " << localized.position_max
            << " m (after the first scan)\n";

  // The map is exactly the saved one, hit records included.
  const io::HexMapData after = io::CaptureSlamMap(localizing);
  ASSERT_EQ(after.levels.size(), saved.levels.size());
  for (std::size_t k = 0; k < saved.levels.size(); ++k) {
    EXPECT_EQ(after.levels[k].log_odds, saved.levels[k].log_odds) << "level " << k;
    ASSERT_EQ(after.levels[k].hits.size(), saved.levels[k].hits.size()) << "level " << k;
    ASSERT_FALSE(saved.levels[k].hits.empty());
    for (std::size_t i = 0; i < saved.levels[k].hits.size(); ++i) {
      const io::HexMapHit& a = after.levels[k].hits[i];
      const io::HexMapHit& b = saved.levels[k].hits[i];
      EXPECT_EQ(a.cell, b.cell);
      EXPECT_EQ(a.count, b.count);
      EXPECT_NEAR(a.mean_x, b.mean_x, 1e-7);
      EXPECT_NEAR(a.mean_y, b.mean_y, 1e-7);
    }
  }
}

TEST(LocalizationLoadTest, ARefusedMapLeavesSlamAsItWas) {
  testing_util::TempDir dir;
  Slam hex(RoomOptions("hex"));
  EXPECT_NE(io::LoadSlamMap(dir.File("missing.hexmap"), &hex).find("missing.hexmap"),
            std::string::npos);

  // A square map offered to a hex Slam.
  Slam square(RoomOptions("square"));
  const sim::RoomDrive drive = sim::MakeRoomDrive(360);
  square.Reset(drive.truth.front());
  std::mt19937_64 rng(3);
  square.ProcessScan(sim::SimulateScan(drive.world, drive.truth[0], drive.lidar, 0.0, &rng));
  const std::string path = dir.File("square.hexmap");
  ASSERT_EQ(io::WriteHexMapFile(path, io::CaptureSlamMap(square)), "");
  const std::string error = io::LoadSlamMap(path, &hex);
  EXPECT_NE(error.find("not a hex"), std::string::npos) << error;
  EXPECT_NE(error.find("square.hexmap"), std::string::npos) << error;
  // Still without a map: the next scan seeds one.
  const ScanReport report =
      hex.ProcessScan(sim::SimulateScan(drive.world, drive.truth[0], drive.lidar, 0.0, &rng));
  EXPECT_EQ(report.outcome, ScanOutcome::kInitialized);
}

}  // namespace
}  // namespace hex_slam
