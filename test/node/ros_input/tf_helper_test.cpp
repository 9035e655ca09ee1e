#include "ros_input/tf_helper.h"

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "test_rotations.h"

namespace hex_slam {
namespace node {
namespace {

using testing_util::MakeTransform;
using testing_util::Pitch;
using testing_util::Roll;
using testing_util::Yaw;

// Property, against Eigen's 3D transform as the oracle: a beam point mapped by the mount tf
// gives lands where the 3D transform puts it (x, y), at the height above the laser it gives (z),
// for level, upside-down, and arbitrarily tilted lasers.
TEST(TfHelperTest, MountedBeamsLandWhereTheThreeDTransformPutsThem) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), offset(-0.5, 0.5), tilt(-0.6, 0.6);
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Quaterniond rotation = Yaw(angle(rng));
    const int kind = trial % 3;  // level, upside down, tilted
    if (kind == 1) rotation = rotation * (trial % 2 ? Roll(M_PI) : Pitch(M_PI));
    if (kind == 2) rotation = rotation * Roll(tilt(rng)) * Pitch(tilt(rng));
    const Eigen::Vector3d translation(offset(rng), offset(rng), 0.3);
    const MountLookup found = MountFromTransform(MakeTransform(translation, rotation));
    EXPECT_EQ(found.upside_down, kind == 1);
    EXPECT_EQ(found.mount.level(), kind == 0) << "trial " << trial;
    if (kind != 2) {
      EXPECT_NEAR(found.tilt, 0.0, 1e-6);
    }
    for (int k = 0; k < 5; ++k) {
      const double a = angle(rng), r = 0.5 + 3.0 * std::abs(offset(rng));
      const Eigen::Vector2d beam(r * std::cos(a), r * std::sin(a));
      const Eigen::Vector3d in_base = rotation * Eigen::Vector3d(beam.x(), beam.y(), 0.0) +
                                      translation;
      EXPECT_NEAR((found.mount.ToBase(beam) - in_base.head<2>()).norm(), 0.0, 1e-9);
      EXPECT_NEAR(found.mount.HeightOf(beam), in_base.z() - translation.z(), 1e-9);
    }
    EXPECT_NEAR((found.mount.origin() - translation.head<2>()).norm(), 0.0, 1e-12);
  }
}

// tf2 refuses NaN but stores inf: a transform with inf (a broken odometry driver) must never
// reach the estimate, nor must the transforms interpolated from it.
TEST(TfHelperTest, NonFiniteTransformsAreRefused) {
  ros::Time::init();
  tf2_ros::Buffer buffer;
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "odom";
  t.child_frame_id = "base_link";
  t.transform.rotation.w = 1.0;
  t.header.stamp = ros::Time(10.0);
  ASSERT_TRUE(buffer.setTransform(t, "test"));
  t.header.stamp = ros::Time(10.1);
  t.transform.translation.x = std::numeric_limits<double>::infinity();
  ASSERT_TRUE(buffer.setTransform(t, "test")) << "tf2 stores inf: the node must check";
  const TfHelper helper(&buffer, "base_link");
  std::string error;
  EXPECT_TRUE(helper.Lookup("odom", "base_link", ros::Time(10.0), 0.0, &error).has_value());
  for (double stamp : {10.05, 10.1}) {
    EXPECT_FALSE(helper.Lookup("odom", "base_link", ros::Time(stamp), 0.0, &error).has_value())
        << stamp;
    EXPECT_NE(error.find("non-finite"), std::string::npos) << error;
  }
}

// The laser's mount on the base at `stamp`, pitched by `pitch`, on tf (not tf_static).
geometry_msgs::TransformStamped MountTransform(double stamp, double pitch) {
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "base_link";
  t.header.stamp = ros::Time(stamp);
  t.child_frame_id = "laser";
  t.transform = MakeTransform(Eigen::Vector3d(0.2, 0.0, 0.3), Pitch(pitch));
  return t;
}

// A scan stamped past tf's latest mount (a busy machine's listener lags): the latest stands in
// only for a mount that does not move. One that pitches would tilt the scan by the pitch it has
// turned since, lifting floor returns over the height filter: nothing is returned, with the
// reason. Scans tf has reached get the mount at their stamp, interpolated.
TEST(TfHelperTest, OnlyAFixedMountIsStoodInForByItsLatestTransform) {
  ros::Time::init();
  for (const bool moving : {false, true}) {
    tf2_ros::Buffer buffer;
    for (int k = 0; k <= 10; ++k) {
      ASSERT_TRUE(buffer.setTransform(MountTransform(100.0 + 0.1 * k, moving ? 0.01 * k : 0.05),
                                      "test"));
    }
    TfHelper helper(&buffer, "base_link");
    std::string error;
    const std::optional<MountLookup> inside =
        helper.Mount("laser", ros::Time(100.55), 0.0, 0.0, &error);
    ASSERT_TRUE(inside.has_value()) << error;
    EXPECT_FALSE(inside->latest);
    EXPECT_NEAR(inside->tilt, moving ? 0.055 : 0.05, 1e-9);
    const std::optional<MountLookup> late =
        helper.Mount("laser", ros::Time(101.05), 0.0, 0.0, &error);
    EXPECT_EQ(late.has_value(), !moving) << "moving " << moving;
    if (moving) {
      EXPECT_NE(error.find("moves"), std::string::npos) << error;
    } else {
      ASSERT_TRUE(late.has_value());
      EXPECT_TRUE(late->latest);
      EXPECT_NEAR(late->tilt, 0.05, 1e-9);
    }
  }
}

// A mount published once on tf (not tf_static) has nothing to be seen moving by: it stands in
// for every later scan, as before.
TEST(TfHelperTest, AMountPublishedOnceStandsInForLaterScans) {
  ros::Time::init();
  tf2_ros::Buffer buffer;
  ASSERT_TRUE(buffer.setTransform(MountTransform(100.0, 0.05), "test"));
  TfHelper helper(&buffer, "base_link");
  std::string error;
  const std::optional<MountLookup> found =
      helper.Mount("laser", ros::Time(130.0), 0.0, 0.0, &error);
  ASSERT_TRUE(found.has_value()) << error;
  EXPECT_TRUE(found->latest);
  EXPECT_NEAR(found->tilt, 0.05, 1e-9);
}

TEST(TfHelperTest, TiltIsMeasured) {
  const MountLookup found =
      MountFromTransform(MakeTransform(Eigen::Vector3d::Zero(), Yaw(0.4) * Pitch(0.2)));
  EXPECT_FALSE(found.upside_down);
  EXPECT_NEAR(found.tilt, 0.2, 1e-9);
  EXPECT_NEAR(found.planar.theta, 0.4, 1e-9);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
