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
    if (kind != 2) EXPECT_NEAR(found.tilt, 0.0, 1e-6);
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
