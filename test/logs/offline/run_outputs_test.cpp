#include "hex_slam/logs/offline/run_outputs.h"

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/io/map_server_io.h"
#include "hex_slam/io/image_io.h"
#include "hex_slam/logs/offline/offline_runner.h"
#include "sim_log.h"

namespace hex_slam {
namespace logs {
namespace {

TEST(RunOutputsTest, WritesTheTrajectoryTheMapsAndThePictures) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(180);
  const std::vector<LogScan> scans = test::SimulatedLog(drive, 2, 100);
  for (const char* lattice : {"hex", "square"}) {
    SlamOptions options;
    options.lattice = lattice;
    Slam slam(options);
    const OfflineRun run = RunOffline(scans, OfflineOptions(), &slam);
    const std::string dir = ::testing::TempDir() + "/run_outputs_" + lattice + "/a/b";
    std::vector<Pose2> odometry;
    for (const LogScan& s : scans) odometry.push_back(*s.odometry);
    std::vector<std::string> written;
    ASSERT_EQ(WriteRunOutputs(dir, slam, run.trajectory, odometry, RunOutputOptions(), &written), "");
    EXPECT_EQ(written.size(), 6u);
    // The native map loads back into a Slam of the same options (localization's starting point).
    Slam again(options);
    EXPECT_EQ(io::LoadSlamMap(dir + "/map.hexmap", &again), "");
    std::vector<io::StampedPose> trajectory;
    ASSERT_EQ(io::ReadTumTrajectory(dir + "/trajectory.tum", &trajectory), "");
    ASSERT_EQ(trajectory.size(), scans.size());
    EXPECT_NEAR(trajectory.back().stamp, scans.back().scan.stamp, 1e-6);
    io::OccupancyRaster raster;
    ASSERT_EQ(io::LoadMapServerMap(dir + "/map.yaml", &raster), "");
    EXPECT_GT(raster.width, 50);
    io::Image picture;
    ASSERT_EQ(io::ReadGrayImage(dir + "/" + lattice + "_map.png", &picture), "");
    ASSERT_EQ(io::ReadGrayImage(dir + "/trajectory.png", &picture), "");
    EXPECT_LE(std::max(picture.width, picture.height), RunOutputOptions().max_trajectory_image_side + 1);
    EXPECT_EQ(std::system(("rm -rf " + ::testing::TempDir() + "/run_outputs_" + lattice).c_str()), 0);
  }
}

TEST(RunOutputsTest, AnUnwritableFolderIsAnError) {
  Slam slam((SlamOptions()));
  std::vector<std::string> written;
  const std::string error =
      WriteRunOutputs("/proc/hex_slam_no/out", slam, {}, {}, RunOutputOptions(), &written);
  EXPECT_NE(error.find("cannot create"), std::string::npos) << error;
  EXPECT_TRUE(written.empty());
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
