#include "hex_slam/sensor/sensor_mount.h"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace {

Eigen::Matrix3d Rotation(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// A level mount, given as a pose or as a 3D rotation about z, maps points exactly as the pose:
// live runs (3D tf) and offline runs (planar poses) see the same numbers.
TEST(SensorMountTest, ALevelMountIsItsPoseBitForBit) {
  const Pose2 pose(0.2, -0.1, 2.5);
  const SensorMount from_pose(pose);
  const SensorMount from_rotation(Rotation(0.0, 0.0, pose.theta),
                                  Eigen::Vector3d(pose.x, pose.y, 0.4));
  EXPECT_TRUE(from_rotation.level());
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(-3.2, 7.1)}) {
    EXPECT_EQ(from_pose.ToBase(p), pose * p);
    EXPECT_NEAR((from_rotation.ToBase(p) - pose * p).norm(), 0.0, 1e-12);
    EXPECT_EQ(from_rotation.HeightOf(p), 0.0);
  }
}

// Against Eigen's 3D transform: any tilted mount puts a beam point where the 3D transform does
// (x, y), at the height above the laser it gives.
TEST(SensorMountTest, ATiltedMountProjectsLikeTheThreeDTransform) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), tilt(-0.7, 0.7), u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d r = Rotation(tilt(rng), tilt(rng), angle(rng));
    const Eigen::Vector3d t(u(rng), u(rng), 0.3);
    const SensorMount mount(r, t);
    const Eigen::Vector2d p(u(rng), u(rng));
    const Eigen::Vector3d oracle = r * Eigen::Vector3d(p.x(), p.y(), 0.0) + t;
    EXPECT_NEAR((mount.ToBase(p) - oracle.head<2>()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(mount.HeightOf(p), oracle.z() - t.z(), 1e-12);
    EXPECT_EQ(mount.origin(), t.head<2>());
  }
}

// The core drops a tilted laser's points outside (laser_z_min_value, laser_z_max_value): with a
// 0.3 rad pitch, beams ahead end below the laser and beams behind above it.
TEST(SensorMountTest, SlamKeepsOnlyPointsWithinTheHeightLimits) {
  SlamOptions options;
  options.laser_min_dist = 0.0;
  options.laser_z_min_value = -0.2;
  options.laser_z_max_value = 0.2;
  Slam slam(options);
  LaserScan scan;
  scan.stamp = 1.0;
  scan.angle_min = -M_PI;
  scan.angle_increment = 2.0 * M_PI / 360.0;
  scan.angle_max = scan.angle_min + 359 * scan.angle_increment;
  scan.range_min = 0.1;
  scan.range_max = 10.0;
  scan.ranges.assign(360, 1.0f);  // every point 1 m from the laser: height -sin(0.3) cos(a)
  const SensorMount pitched(Rotation(0.0, 0.3, 0.0), Eigen::Vector3d(0.0, 0.0, 0.5));
  const ScanReport report = slam.ProcessScan(scan, pitched);
  int expected_outside = 0;
  for (int i = 0; i < 360; ++i) {
    const double a = scan.angle_min + i * scan.angle_increment;
    expected_outside += std::abs(std::sin(0.3) * std::cos(a)) >= 0.2;
  }
  ASSERT_GT(expected_outside, 100);
  EXPECT_EQ(report.beams.outside_height, expected_outside);
  EXPECT_EQ(report.beams.valid, 360 - expected_outside);
}

}  // namespace
}  // namespace hex_slam
