#include "hex_slam/logs/bag_writer.h"

#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "hex_slam/logs/bag_reader.h"
#include "sim_log.h"

namespace hex_slam {
namespace logs {
namespace {

TEST(BagWriterTest, ABagWrittenFromALogReadsBackAsTheSameLog) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(90);
  std::vector<LogScan> scans = test::SimulatedLog(drive, 1, 40);
  for (LogScan& s : scans) s.sensor_pose = Pose2(0.15, -0.05, 0.02);
  scans[10].scan.stamp += 0.5;  // stamped late
  const std::string path = ::testing::TempDir() + "/bag_writer_test.bag";
  BagWriteReport report;
  ASSERT_EQ(WriteLogAsBag(scans, path, BagWriteOptions(), &report), "");
  EXPECT_EQ(report.scans, 40);
  EXPECT_EQ(report.odometry, 40);
  EXPECT_GE(report.stamps_lowered, 1);
  EXPECT_FALSE(report.mounting_varies);

  BagLog log;
  ASSERT_EQ(ReadBag(path, BagReadOptions(), &log), "");
  ASSERT_EQ(log.scans.size(), scans.size());
  EXPECT_EQ(log.dropped_no_transform, 0);
  EXPECT_EQ(log.scans_without_odometry, 0);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const LogScan& got = log.scans[i];
    if (i > 0) {
      EXPECT_LT(log.scans[i - 1].scan.stamp, got.scan.stamp) << i;
    }
    if (i != 10) {
      EXPECT_NEAR(got.scan.stamp, scans[i].scan.stamp, 1e-6) << i;
    }
    EXPECT_EQ(got.scan.ranges, scans[i].scan.ranges);
    EXPECT_NEAR(got.sensor_pose.x, 0.15, 1e-9);
    EXPECT_NEAR(got.sensor_pose.theta, 0.02, 1e-9);
    ASSERT_TRUE(got.odometry.has_value());
    EXPECT_NEAR(got.odometry->x, scans[i].odometry->x, 1e-9) << i;
    EXPECT_NEAR(NormalizeAngle(got.odometry->theta - scans[i].odometry->theta), 0.0, 1e-9);
  }
  // The mounting is latched, so a replay re-sends it to late subscribers.
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery("/tf_static"));
  ASSERT_EQ(view.getConnections().size(), 1u);
  const auto& header = *view.getConnections()[0]->header;
  EXPECT_EQ(header.at("latching"), "1");
  EXPECT_EQ(header.at("type"), "tf2_msgs/TFMessage");
  bag.close();
  std::remove(path.c_str());
}

TEST(BagWriterTest, FailuresLeaveNoFileBehind) {
  BagWriteReport report;
  EXPECT_NE(WriteLogAsBag({}, "/tmp/never.bag", BagWriteOptions(), &report), "");
  const sim::RoomDrive drive = sim::MakeRoomDrive(90);
  const std::vector<LogScan> scans = test::SimulatedLog(drive, 1, 3);
  const std::string error =
      WriteLogAsBag(scans, "/proc/hex_slam_no/x.bag", BagWriteOptions(), &report);
  EXPECT_NE(error.find("cannot write"), std::string::npos) << error;
  std::vector<LogScan> bad = scans;
  bad[0].scan.stamp = -5.0;
  EXPECT_NE(WriteLogAsBag(bad, "/tmp/never.bag", BagWriteOptions(), &report).find("ROS time"),
            std::string::npos);
  EXPECT_FALSE(std::ifstream("/tmp/never.bag").good());
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
