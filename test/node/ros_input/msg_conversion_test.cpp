#include "ros_input/msg_conversion.h"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "test_rotations.h"

namespace hex_slam {
namespace node {
namespace {

using testing_util::Pitch;
using testing_util::Roll;
using testing_util::ToMsg;
using testing_util::Yaw;

// YawOf (pose_msgs.h) on a full 3D rotation: a small roll and pitch (a robot on a ramp) barely
// changes the heading.
TEST(MsgConversionTest, YawOfATiltedRotationIsItsHeading) {
  EXPECT_NEAR(YawOf(ToMsg(Yaw(0.7) * Roll(0.05) * Pitch(-0.04))), 0.7, 0.01);
}

TEST(MsgConversionTest, SlamCloudHoldsTheUsableReturnsInTheScansFrame) {
  sensor_msgs::LaserScan msg;
  msg.header.frame_id = "laser";
  msg.header.stamp = ros::Time(3, 0);
  msg.angle_min = -M_PI / 2;
  msg.angle_increment = M_PI / 2;
  msg.range_min = 0.1f;
  msg.range_max = 8.0f;
  // -90°: 2 m; 0°: NaN; 90°: 0.05 m (below range_min); 180°: 9 m (above range_max); 270°: 3 m.
  msg.ranges = {2.0f, NAN, 0.05f, 9.0f, 3.0f};
  const sensor_msgs::PointCloud cloud = ToPointCloudMsg(msg, 0.0, 30.0);
  EXPECT_EQ(cloud.header.frame_id, "laser");
  EXPECT_EQ(cloud.header.stamp, msg.header.stamp);
  ASSERT_EQ(cloud.points.size(), 2u);
  EXPECT_NEAR(cloud.points[0].x, 0.0, 1e-6);
  EXPECT_NEAR(cloud.points[0].y, -2.0, 1e-6);
  EXPECT_NEAR(cloud.points[1].x, 0.0, 1e-6);
  EXPECT_NEAR(cloud.points[1].y, -3.0, 1e-6);
  // laser_max_dist 2.5 m drops the 3 m return too.
  EXPECT_EQ(ToPointCloudMsg(msg, 0.4, 2.5).points.size(), 1u);
}

TEST(MsgConversionTest, CovarianceGoesToTheXYYawEntries) {
  Eigen::Matrix3d c;
  c << 1, 2, 3,  //
      2, 4, 5,   //
      3, 5, 6;
  const boost::array<double, 36> m = ToCovarianceMsg(c);
  EXPECT_EQ(m[0], 1);
  EXPECT_EQ(m[1], 2);
  EXPECT_EQ(m[5], 3);
  EXPECT_EQ(m[6], 2);
  EXPECT_EQ(m[7], 4);
  EXPECT_EQ(m[11], 5);
  EXPECT_EQ(m[30], 3);
  EXPECT_EQ(m[31], 5);
  EXPECT_EQ(m[35], 6);
  EXPECT_EQ(m[14], 0);  // z
  EXPECT_EQ(m[21], 0);  // roll
  EXPECT_EQ(m[28], 0);  // pitch
}

TEST(MsgConversionTest, FrameIdsLoseLeadingSlashes) {
  EXPECT_EQ(CleanFrameId("/laser"), "laser");
  EXPECT_EQ(CleanFrameId("//laser"), "laser");
  EXPECT_EQ(CleanFrameId("base_link"), "base_link");
  EXPECT_EQ(CleanFrameId("/"), "");
  EXPECT_EQ(CleanFrameId(""), "");
}

TEST(MsgConversionTest, OccupancyGridCarriesTheRaster) {
  io::OccupancyRaster raster;
  raster.resolution = 0.05;
  raster.origin = Eigen::Vector2d(-1.0, 2.0);
  raster.width = 3;
  raster.height = 2;
  raster.data = {0, 100, -1, -1, 0, 100};
  const nav_msgs::OccupancyGrid grid = ToOccupancyGridMsg(raster, "map", ros::Time(5));
  EXPECT_EQ(grid.header.frame_id, "map");
  EXPECT_FLOAT_EQ(grid.info.resolution, 0.05f);
  EXPECT_EQ(grid.info.width, 3u);
  EXPECT_EQ(grid.info.height, 2u);
  EXPECT_DOUBLE_EQ(grid.info.origin.position.x, -1.0);
  EXPECT_DOUBLE_EQ(grid.info.origin.position.y, 2.0);
  EXPECT_DOUBLE_EQ(grid.info.origin.orientation.w, 1.0);
  EXPECT_EQ(grid.data, raster.data);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
