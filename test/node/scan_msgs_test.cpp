#include "scan_msgs.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

TEST(ScanMsgsTest, ScanFieldsAreCopied) {
  sensor_msgs::LaserScan msg;
  msg.header.stamp = ros::Time(12, 500000000);
  msg.angle_min = -1.0;
  msg.angle_max = 1.0;
  msg.angle_increment = 0.5;
  msg.range_min = 0.1f;
  msg.range_max = 8.0f;
  msg.ranges = {1.0f, NAN, INFINITY, -1.0f, 2.0f};
  const LaserScan scan = ScanFromMsg(msg, msg.header.stamp.toSec());
  EXPECT_DOUBLE_EQ(scan.stamp, 12.5);
  EXPECT_DOUBLE_EQ(scan.angle_min, -1.0);
  EXPECT_DOUBLE_EQ(scan.angle_increment, 0.5);
  EXPECT_FLOAT_EQ(scan.range_max, 8.0f);
  ASSERT_EQ(scan.ranges.size(), 5u);
  EXPECT_TRUE(std::isnan(scan.ranges[1]));  // left for the core's sanitizer to count and drop
}

}  // namespace
}  // namespace hex_slam
