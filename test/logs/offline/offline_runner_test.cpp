#include "hex_slam/logs/offline/offline_runner.h"

#include <gtest/gtest.h>

#include "sim_log.h"

namespace hex_slam {
namespace logs {
namespace {

double MaxError(const OfflineRun& run, const sim::RoomDrive& drive) {
  double worst = 0.0;
  for (std::size_t i = 0; i < run.trajectory.size(); ++i) {
    worst = std::max(worst, (run.trajectory[i].pose.translation() - drive.truth[i].translation()).norm());
  }
  return worst;
}

TEST(OfflineRunnerTest, BackwardStampsAreProcessedInLogOrderAndWrittenAsLogged) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(180);
  std::vector<LogScan> scans = test::SimulatedLog(drive, 3, 200);
  // Two scans stamped late, as in the Intel log.
  scans[50].scan.stamp += 0.35;
  scans[120].scan.stamp += 0.9;
  Slam slam((SlamOptions()));
  slam.Reset(drive.truth.front());
  const OfflineRun run = RunOffline(scans, OfflineOptions(), &slam);
  ASSERT_EQ(run.trajectory.size(), scans.size());
  EXPECT_EQ(run.count(ScanOutcome::kTimeWentBackwards), 0);
  EXPECT_EQ(run.count(ScanOutcome::kMatched), 199);
  EXPECT_GE(run.stamps_lowered, 2);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    EXPECT_EQ(run.trajectory[i].stamp, scans[i].scan.stamp) << i;
  }
  EXPECT_EQ(run.scan_ms.size(), scans.size());
  EXPECT_NEAR(run.log_seconds, scans.back().scan.stamp - scans.front().scan.stamp, 1e-9);
  EXPECT_GT(run.RealtimeFactor(), 0.0);
  EXPECT_LT(MaxError(run, drive), 0.05);
}

TEST(OfflineRunnerTest, WithoutOdometryTheLogsOdometryIsIgnored) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(180);
  std::vector<LogScan> scans = test::SimulatedLog(drive, 4, 150);
  // Odometry that lies badly, jumping 1 m back and forth: used, it throws the matcher off.
  for (std::size_t i = 0; i < scans.size(); ++i) scans[i].odometry = Pose2(i % 2 == 0 ? 0.0 : 1.0, 0, 0);
  OfflineOptions no_odometry;
  no_odometry.use_odometry = false;
  Slam slam((SlamOptions()));
  slam.Reset(drive.truth.front());
  EXPECT_LT(MaxError(RunOffline(scans, no_odometry, &slam), drive), 0.05);
  slam.Reset(drive.truth.front());
  EXPECT_GT(MaxError(RunOffline(scans, OfflineOptions(), &slam), drive), 0.3);
}

TEST(OfflineRunnerTest, GivenSensorPoseReplacesTheLogsAndRejectionsAreReported) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(180);
  std::vector<LogScan> scans = test::SimulatedLog(drive, 5, 60);
  for (LogScan& s : scans) s.sensor_pose = Pose2(5.0, 0, 0);  // a wrong mounting in the log
  scans[30].scan.ranges.clear();                            // a broken scan
  OfflineOptions options;
  options.sensor_pose = Pose2();
  Slam slam((SlamOptions()));
  slam.Reset(drive.truth.front());
  int calls = 0;
  const OfflineRun run = RunOffline(scans, options, &slam, [&calls](std::size_t done, double) {
    ++calls;
    EXPECT_GE(done, 1u);
  });
  EXPECT_EQ(calls, 60);
  EXPECT_EQ(run.count(ScanOutcome::kInvalidScan), 1);
  EXPECT_NE(run.first_rejection.find("scan 30"), std::string::npos);
  EXPECT_LT(MaxError(run, drive), 0.05);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
