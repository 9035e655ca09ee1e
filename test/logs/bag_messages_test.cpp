#include "hex_slam/logs/bag_messages.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <ros/serialization.h>

namespace hex_slam {
namespace logs {
namespace {

template <class Msg>
std::vector<std::uint8_t> Bytes(const Msg& msg) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(msg));
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(out, msg);
  return bytes;
}

void PutU32(std::vector<std::uint8_t>* bytes, std::size_t at, std::uint32_t value) {
  std::memcpy(bytes->data() + at, &value, sizeof value);
}

sensor_msgs::LaserScan Scan() {
  sensor_msgs::LaserScan s;
  s.header.stamp = ros::Time(12.5);
  s.header.frame_id = "laser";
  s.angle_min = -1.0f;
  s.angle_max = 1.0f;
  s.angle_increment = 0.5f;
  s.range_min = 0.1f;
  s.range_max = 10.0f;
  s.ranges = {1.0f, std::numeric_limits<float>::quiet_NaN(), 3.0f,
              std::numeric_limits<float>::infinity(), -1.0f};
  s.intensities = {5.0f};
  return s;
}

// The offset of a scan's ranges length field: seq, stamp, frame_id, seven floats.
std::size_t RangesLengthAt(const sensor_msgs::LaserScan& s) {
  return 4 + 8 + 4 + s.header.frame_id.size() + 7 * 4;
}

TEST(BagMessagesTest, AWellFormedScanRoundTripsWithItsRep117Ranges) {
  const sensor_msgs::LaserScan in = Scan();
  const std::vector<std::uint8_t> bytes = Bytes(in);
  sensor_msgs::LaserScan out;
  ASSERT_EQ(DecodeLaserScan(bytes.data(), bytes.size(), &out), "");
  EXPECT_EQ(out.header.frame_id, "laser");
  ASSERT_EQ(out.ranges.size(), 5u);
  EXPECT_TRUE(std::isnan(out.ranges[1]));  // the sanitizer's to count, not the reader's to refuse
  EXPECT_EQ(out.ranges[4], -1.0f);
  EXPECT_EQ(out.intensities.size(), 1u);
}

TEST(BagMessagesTest, ALengthFieldBeyondTheDataIsRefusedBeforeAllocation) {
  // Issue 12: a LaserScan whose ranges length read 3.4e9 made roscpp allocate 13 GB before its
  // "Buffer Overrun". Here the length is checked against the bytes first.
  const sensor_msgs::LaserScan in = Scan();
  std::vector<std::uint8_t> bytes = Bytes(in);
  PutU32(&bytes, RangesLengthAt(in), 3405691582u);
  sensor_msgs::LaserScan out;
  EXPECT_EQ(DecodeLaserScan(bytes.data(), bytes.size(), &out),
            "ranges declares 3405691582 elements, more than 65536");
  PutU32(&bytes, RangesLengthAt(in), 60000u);  // within the cap, beyond the data
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size(), &out).find("ranges needs 240000 bytes"),
            std::string::npos);
  bytes = Bytes(in);
  PutU32(&bytes, 4 + 8, 0xFFFFFFFFu);  // frame_id's length
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size(), &out).find("header.frame_id"),
            std::string::npos);
  bytes = Bytes(in);
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size() - 1, &out).find("truncated"),
            std::string::npos);
  bytes.push_back(0);
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size(), &out).find("1 bytes past"),
            std::string::npos);
  EXPECT_NE(DecodeLaserScan(bytes.data(), kMaxBagMessageBytes + 1, &out).find("more than the"),
            std::string::npos);
}

TEST(BagMessagesTest, ScanFieldsMustBeFiniteAndStampsValid) {
  sensor_msgs::LaserScan in = Scan();
  in.angle_increment = std::numeric_limits<float>::infinity();
  std::vector<std::uint8_t> bytes = Bytes(in);
  sensor_msgs::LaserScan out;
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size(), &out).find("angle_increment = inf is not "
                                                                   "a finite number"),
            std::string::npos);
  in = Scan();
  in.range_max = 1e30f;
  bytes = Bytes(in);
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size(), &out).find("range_max"), std::string::npos);
  in = Scan();
  bytes = Bytes(in);
  PutU32(&bytes, 8, 1500000000u);  // stamp.nsec
  EXPECT_NE(DecodeLaserScan(bytes.data(), bytes.size(), &out).find("header.stamp.nsec"),
            std::string::npos);
}

geometry_msgs::TransformStamped Transform(double x) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time(3.0);
  t.header.frame_id = "odom";
  t.child_frame_id = "base_link";
  t.transform.translation.x = x;
  t.transform.rotation.w = 1.0;
  return t;
}

TEST(BagMessagesTest, TransformsMustBeFiniteBoundedAndUnitRotations) {
  // Issue 12: a bag whose /tf odom -> base_link had x = -inf or 1e15 crashed hex_slam_offline
  // (tf2 refuses NaN but stores inf).
  tf2_msgs::TFMessage in;
  in.transforms = {Transform(1.0), Transform(-std::numeric_limits<double>::infinity())};
  std::vector<std::uint8_t> bytes = Bytes(in);
  tf2_msgs::TFMessage out;
  EXPECT_EQ(DecodeTfMessage(bytes.data(), bytes.size(), &out),
            "transforms[1] transform odom -> base_link: translation.x = -inf is not a finite "
            "number");
  in.transforms[1] = Transform(1e15);
  bytes = Bytes(in);
  EXPECT_NE(DecodeTfMessage(bytes.data(), bytes.size(), &out).find("translation.x = 1e+15 is "
                                                                   "beyond ±1e+07 m"),
            std::string::npos);
  in.transforms[1] = Transform(2.0);
  in.transforms[1].transform.rotation.w = 0.5;
  bytes = Bytes(in);
  EXPECT_NE(DecodeTfMessage(bytes.data(), bytes.size(), &out).find("not a unit quaternion"),
            std::string::npos);
  in.transforms[1] = Transform(2.0);
  bytes = Bytes(in);
  ASSERT_EQ(DecodeTfMessage(bytes.data(), bytes.size(), &out), "");
  EXPECT_EQ(out.transforms.size(), 2u);
  // A count of 4e9 transforms in 200 bytes: refused when the bytes run out, not allocated.
  PutU32(&bytes, 0, 4000000000u);
  EXPECT_NE(DecodeTfMessage(bytes.data(), bytes.size(), &out).find("transforms[2]"),
            std::string::npos);
}

TEST(BagMessagesTest, OdometryPosesMustBeFiniteAndBounded) {
  // Issue 12: /odom with x = NaN, inf or 1e15 crashed hex_slam_offline.
  for (double x : {std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity(), 1e15}) {
    nav_msgs::Odometry in;
    in.header.stamp = ros::Time(4.0);
    in.pose.pose.position.x = x;
    in.pose.pose.orientation.w = 1.0;
    const std::vector<std::uint8_t> bytes = Bytes(in);
    nav_msgs::Odometry out;
    EXPECT_NE(DecodeOdometry(bytes.data(), bytes.size(), &out).find("pose.pose.position.x"),
              std::string::npos)
        << x;
  }
  nav_msgs::Odometry ok;
  ok.pose.pose.position.x = 5.0;
  ok.pose.pose.orientation.z = 1.0;
  const std::vector<std::uint8_t> bytes = Bytes(ok);
  nav_msgs::Odometry out;
  ASSERT_EQ(DecodeOdometry(bytes.data(), bytes.size(), &out), "");
  EXPECT_EQ(out.pose.pose.position.x, 5.0);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
