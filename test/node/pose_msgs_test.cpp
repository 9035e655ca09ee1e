#include "pose_msgs.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

TEST(PoseMsgsTest, YawAndPoseRoundTrip) {
  for (double yaw : {0.0, 0.3, -1.2, 3.0, -3.1}) {
    EXPECT_NEAR(YawOf(QuaternionFromYaw(yaw)), yaw, 1e-12);
    const Pose2 back = PoseFromMsg(ToPoseMsg(Pose2(1.5, -2.0, yaw)));
    EXPECT_NEAR(back.x, 1.5, 1e-12);
    EXPECT_NEAR(back.y, -2.0, 1e-12);
    EXPECT_NEAR(back.theta, yaw, 1e-12);
    const Pose2 t = PoseFromTransform(ToTransformMsg(Pose2(0.2, 0.1, yaw)));
    EXPECT_NEAR(t.theta, yaw, 1e-12);
  }
}

TEST(PoseMsgsTest, StampedTransformNamesItsFramesAndCarriesThePose) {
  const ros::Time stamp(12.5);
  const geometry_msgs::TransformStamped t =
      ToTransformStampedMsg(Pose2(1.0, -0.5, 0.4), stamp, "odom", "base_link");
  EXPECT_EQ(t.header.stamp, stamp);
  EXPECT_EQ(t.header.frame_id, "odom");
  EXPECT_EQ(t.child_frame_id, "base_link");
  const Pose2 back = PoseFromTransform(t.transform);
  EXPECT_NEAR(back.x, 1.0, 1e-12);
  EXPECT_NEAR(back.y, -0.5, 1e-12);
  EXPECT_NEAR(back.theta, 0.4, 1e-12);
  // A unit quaternion about z only.
  EXPECT_DOUBLE_EQ(t.transform.rotation.x, 0.0);
  EXPECT_DOUBLE_EQ(t.transform.rotation.y, 0.0);
}

}  // namespace
}  // namespace hex_slam
