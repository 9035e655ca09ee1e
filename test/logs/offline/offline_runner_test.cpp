#include "hex_slam/logs/offline/offline_runner.h"

#include <gtest/gtest.h>

#include <chrono>

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

TEST(OfflineRunnerTest, PacedRunHandsScansOverNoSoonerThanTheirStampsAndChangesNoPose) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(180);
  const std::vector<LogScan> scans = test::SimulatedLog(drive, 6, 40);
  SlamOptions single_map;
  single_map.loop_closure.enabled = false;  // deterministic: no worker beside the scans
  Slam slam(single_map);
  slam.Reset(drive.truth.front());
  const OfflineRun fast = RunOffline(scans, OfflineOptions(), &slam);
  OfflineOptions paced;
  paced.pace = 20.0;
  slam.Reset(drive.truth.front());
  const auto start = std::chrono::steady_clock::now();
  const OfflineRun run = RunOffline(scans, paced, &slam);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The last scan was due at the log's span over the pace: the run cannot end sooner.
  EXPECT_GE(elapsed, (scans.back().scan.stamp - scans.front().scan.stamp) / paced.pace);
  ASSERT_EQ(run.trajectory.size(), fast.trajectory.size());
  for (std::size_t i = 0; i < run.trajectory.size(); ++i) {
    EXPECT_EQ(run.trajectory[i].pose.translation(), fast.trajectory[i].pose.translation()) << i;
    EXPECT_EQ(run.trajectory[i].pose.theta, fast.trajectory[i].pose.theta) << i;
  }
  // A scan's time on its own core lies within its wall-clock time (measured inside it).
  ASSERT_EQ(run.scan_cpu_ms.size(), scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    EXPECT_GT(run.scan_cpu_ms[i], 0.0) << i;
    EXPECT_LE(run.scan_cpu_ms[i], run.scan_ms[i] + 1e-3) << i;
  }
  // Paced, each pose is timed from the scan's arrival, as the node times it (the poses above:
  // deferring the insertion to after the pose changes none); unpaced there is no arrival.
  ASSERT_EQ(run.pose_latency_ms.size(), scans.size());
  for (double ms : run.pose_latency_ms) EXPECT_GE(ms, 0.0);
  EXPECT_TRUE(fast.pose_latency_ms.empty());
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
