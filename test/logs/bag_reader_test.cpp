#include "hex_slam/logs/bag_reader.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include "test_data.h"

namespace hex_slam {
namespace logs {
namespace {

sensor_msgs::LaserScan Scan(double t, const std::string& frame) {
  sensor_msgs::LaserScan s;
  s.header.stamp = ros::Time(t);
  s.header.frame_id = frame;
  s.angle_min = -1.0f;
  s.angle_increment = 0.5f;
  s.angle_max = 1.0f;
  s.range_min = 0.1f;
  s.range_max = 10.0f;
  s.ranges = {1, 2, 3, 4, 5};
  return s;
}

geometry_msgs::TransformStamped Transform(const std::string& parent, const std::string& child,
                                          double t, double x, double yaw) {
  geometry_msgs::TransformStamped tf;
  tf.header.stamp = ros::Time(t);
  tf.header.frame_id = parent;
  tf.child_frame_id = child;
  tf.transform.translation.x = x;
  tf.transform.rotation.z = std::sin(0.5 * yaw);
  tf.transform.rotation.w = std::cos(0.5 * yaw);
  return tf;
}

class BagReaderTest : public ::testing::Test {
 protected:
  BagReaderTest() : path_(::testing::TempDir() + "/bag_reader_test.bag") {}
  ~BagReaderTest() override { std::remove(path_.c_str()); }

  // Scans at t = 10, 10.1, ... 10.9 s on /scan; what else the bag holds, each test says.
  void Write(bool mounting_tf, bool odometry_tf, bool odometry_topic, const std::string& laser_frame) {
    rosbag::Bag bag(path_, rosbag::bagmode::Write);
    if (mounting_tf) {
      tf2_msgs::TFMessage m;
      m.transforms.push_back(Transform("/base_link", laser_frame, 10.0, 0.2, 0.1));
      bag.write("/tf_static", ros::Time(10.0), m);
    }
    for (int i = 0; i < 10; ++i) {
      const double t = 10.0 + 0.1 * i;
      if (odometry_tf) {
        tf2_msgs::TFMessage m;
        m.transforms.push_back(Transform("odom", "base_link", t, 0.5 * i, 0.0));
        bag.write("/tf", ros::Time(t), m);
      }
      if (odometry_topic && i % 2 == 0) {  // at 5 Hz: scans in between are interpolated
        nav_msgs::Odometry o;
        o.header.stamp = ros::Time(t);
        o.pose.pose.position.x = 0.5 * i;
        o.pose.pose.orientation.w = 1.0;
        bag.write("/odom", ros::Time(t), o);
      }
      bag.write("/scan", ros::Time(t), Scan(t + 0.001, laser_frame));
    }
  }
  std::string path_;
};

TEST_F(BagReaderTest, MountingAndOdometryComeFromTfAndSlashedFramesWork) {
  Write(true, true, false, "/laser");
  BagLog log;
  ASSERT_EQ(ReadBag(path_, BagReadOptions(), &log), "");
  ASSERT_EQ(log.scans.size(), 10u);
  EXPECT_EQ(log.scans_in_bag, 10);
  EXPECT_NE(log.mounting_source.find("tf"), std::string::npos);
  EXPECT_NE(log.odometry_source.find("tf"), std::string::npos);
  const LogScan& s = log.scans[4];
  EXPECT_NEAR(s.scan.stamp, 10.401, 1e-6);
  EXPECT_EQ(s.scan.ranges.size(), 5u);
  EXPECT_NEAR(s.sensor_pose.x, 0.2, 1e-9);
  EXPECT_NEAR(s.sensor_pose.theta, 0.1, 1e-9);
  ASSERT_TRUE(s.odometry.has_value());
  EXPECT_NEAR(s.odometry->x, 2.0 + 0.005, 1e-6);  // tf interpolates 1 ms past the 10.4 s one
}

TEST_F(BagReaderTest, WithoutTfTheLaserSitsAtTheBaseOrWhereItIsGiven) {
  Write(false, false, false, "laser");
  BagLog log;
  ASSERT_EQ(ReadBag(path_, BagReadOptions(), &log), "");
  EXPECT_EQ(log.scans.size(), 10u);
  EXPECT_NE(log.mounting_source.find("identity"), std::string::npos);
  EXPECT_EQ(log.odometry_source, "none");
  EXPECT_EQ(log.scans[0].sensor_pose.x, 0.0);
  EXPECT_FALSE(log.scans[0].odometry.has_value());
  BagReadOptions given;
  given.sensor_pose = Pose2(0.3, 0, M_PI);
  ASSERT_EQ(ReadBag(path_, given, &log), "");
  EXPECT_EQ(log.scans[0].sensor_pose.theta, M_PI);
}

TEST_F(BagReaderTest, OdometryTopicIsInterpolatedToTheScans) {
  Write(true, false, true, "laser");
  BagLog log;
  ASSERT_EQ(ReadBag(path_, BagReadOptions(), &log), "");
  EXPECT_EQ(log.odometry_source, "topic /odom");
  ASSERT_TRUE(log.scans[3].odometry.has_value());
  EXPECT_NEAR(log.scans[3].odometry->x, 1.5 + 0.005, 1e-6);  // between 1.0 at 10.2 s and 2.0 at 10.4 s
  BagReadOptions relative;  // the node's relative names
  relative.scan_topic = "scan";
  relative.odom_topic = "odom";
  ASSERT_EQ(ReadBag(path_, relative, &log), "");
  EXPECT_EQ(log.odometry_source, "topic /odom");
  BagReadOptions off;
  off.read_odometry = false;
  ASSERT_EQ(ReadBag(path_, off, &log), "");
  EXPECT_FALSE(log.scans[3].odometry.has_value());
  BagReadOptions wrong;
  wrong.odom_topic = "/wheel_odom";
  EXPECT_NE(ReadBag(path_, wrong, &log).find("/wheel_odom"), std::string::npos);
}

TEST_F(BagReaderTest, ScansWithoutAMountingTransformAreDroppedNotGuessed) {
  Write(true, true, false, "laser");
  BagReadOptions options;
  options.base_frame = "base_footprint";  // not in this bag's tf
  BagLog log;
  const std::string error = ReadBag(path_, options, &log);
  EXPECT_NE(error.find("no usable scans"), std::string::npos) << error;
  EXPECT_EQ(log.dropped_no_transform, 10);
  EXPECT_NE(log.first_drop.find("base_footprint"), std::string::npos) << log.first_drop;
}

TEST_F(BagReaderTest, MissingTopicCorruptAndMissingFilesAreClearErrors) {
  Write(false, false, false, "laser");
  BagReadOptions options;
  options.scan_topic = "/base_scan";
  BagLog log;
  const std::string error = ReadBag(path_, options, &log);
  EXPECT_NE(error.find("/base_scan"), std::string::npos);
  EXPECT_NE(error.find("it has: /scan"), std::string::npos) << error;
  {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out << "#ROSBAG V2.0\n" << std::string(300, '\x7f');
  }
  EXPECT_NE(ReadBag(path_, BagReadOptions(), &log).find("cannot read the bag"), std::string::npos);
  EXPECT_NE(ReadBag(path_ + ".none", BagReadOptions(), &log).find("cannot read the bag"),
            std::string::npos);
}

// The byte offsets in the file at `path` where `pattern` occurs.
std::vector<std::size_t> Find(const std::string& path, const std::string& pattern,
                              std::string* bytes) {
  std::ifstream in(path, std::ios::binary);
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::vector<std::size_t> at;
  for (std::size_t i = bytes->find(pattern); i != std::string::npos;
       i = bytes->find(pattern, i + 1)) {
    at.push_back(i);
  }
  return at;
}

void Patch(const std::string& path, std::string bytes, std::size_t at, std::uint32_t value) {
  std::memcpy(&bytes[at], &value, sizeof value);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST_F(BagReaderTest, ACorruptScanLengthIsRefusedBeforeAllocatingIt) {
  // Issue 12: a LaserScan whose length field read 3.4e9 took 13 GB before "Buffer Overrun".
  // The bag's scans are on frame "laser": its serialized name is 5, 0, 0, 0, "laser".
  Write(false, false, false, "laser");
  std::string bytes;
  const std::vector<std::size_t> frames = Find(path_, std::string("\x05\0\0\0laser", 9), &bytes);
  ASSERT_EQ(frames.size(), 10u);
  const std::size_t ranges_length = frames[4] + 9 + 7 * 4;
  Patch(path_, bytes, ranges_length, 3405691582u);
  BagLog log;
  EXPECT_EQ(ReadBag(path_, BagReadOptions(), &log),
            path_ + ": /scan message 4 (recorded at 10.400000000 s): ranges declares 3405691582 "
                    "elements, more than 65536");
  BagReadOptions skip;
  skip.skip_bad_messages = true;
  ASSERT_EQ(ReadBag(path_, skip, &log), "");
  EXPECT_EQ(log.scans.size(), 9u);
  EXPECT_EQ(log.bad_messages, 1);
  // The record's own data length beyond the cap: refused before it is read at all.
  const std::size_t data_length = frames[4] - 4 - 8 - 4;
  Patch(path_, bytes, data_length, 0x7fffffffu);
  EXPECT_NE(ReadBag(path_, BagReadOptions(), &log).find("declares 2147483647 bytes"),
            std::string::npos);
}

TEST_F(BagReaderTest, NonFiniteOrHugeOdometryIsRefusedNamingTheMessage) {
  // Issue 12: tf odom -> base_link with x = -inf or 1e15, /odom with x = NaN, inf or 1e15 each
  // crashed hex_slam_offline. Written as the test bag's 4th odometry message.
  for (const double x : {-std::numeric_limits<double>::infinity(), 1e15,
                         std::numeric_limits<double>::quiet_NaN()}) {
    for (const bool topic : {false, true}) {
      {
        rosbag::Bag bag(path_, rosbag::bagmode::Write);
        for (int i = 0; i < 10; ++i) {
          const double t = 10.0 + 0.1 * i;
          const double odom_x = i == 3 ? x : 0.1 * i;
          if (topic) {
            nav_msgs::Odometry o;
            o.header.stamp = ros::Time(t);
            o.pose.pose.position.x = odom_x;
            o.pose.pose.orientation.w = 1.0;
            bag.write("/odom", ros::Time(t), o);
          } else {
            tf2_msgs::TFMessage m;
            m.transforms.push_back(Transform("odom", "base_link", t, odom_x, 0.0));
            bag.write("/tf", ros::Time(t), m);
          }
          bag.write("/scan", ros::Time(t), Scan(t, "base_link"));
        }
      }
      BagLog log;
      const std::string error = ReadBag(path_, BagReadOptions(), &log);
      const std::string field = topic ? "/odom message 3 (recorded at 10.300000000 s): "
                                        "pose.pose.position.x = "
                                      : "/tf message 3 (recorded at 10.300000000 s): "
                                        "transforms[0] transform odom -> base_link: translation.x";
      EXPECT_NE(error.find(field), std::string::npos) << x << ": " << error;
      BagReadOptions skip;
      skip.skip_bad_messages = true;
      ASSERT_EQ(ReadBag(path_, skip, &log), "") << x;
      EXPECT_EQ(log.bad_messages, 1);
      for (const LogScan& s : log.scans) {
        ASSERT_TRUE(s.odometry.has_value());
        EXPECT_LT(std::abs(s.odometry->x), 1.0) << x << " reached a scan's odometry";
      }
    }
  }
}

TEST_F(BagReaderTest, ATfMountingFarFromTheBaseIsRefused) {
  {
    rosbag::Bag bag(path_, rosbag::bagmode::Write);
    tf2_msgs::TFMessage m;
    m.transforms.push_back(Transform("base_link", "laser", 10.0, 65000.0, 0.0));
    bag.write("/tf_static", ros::Time(10.0), m);
    bag.write("/scan", ros::Time(10.0), Scan(10.0, "laser"));
  }
  BagLog log;
  EXPECT_NE(ReadBag(path_, BagReadOptions(), &log).find("the laser sits 65000 m from the base"),
            std::string::npos);
}

TEST(BagReaderDataTest, TheCcnyBagHas360ScansOf681BeamsAndNoTf) {
  const std::string path = test::DataFile(test::kCcnyBag);
  HEX_SLAM_REQUIRE_DATA(path);
  BagLog log;
  ASSERT_EQ(ReadBag(path, BagReadOptions(), &log), "");
  ASSERT_EQ(log.scans.size(), 360u);
  EXPECT_EQ(log.scans[0].scan.ranges.size(), 681u);
  EXPECT_NE(log.mounting_source.find("identity"), std::string::npos);
  EXPECT_EQ(log.odometry_source, "none");
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
