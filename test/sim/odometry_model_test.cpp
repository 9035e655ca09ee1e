#include "hex_slam/sim/odometry_model.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace hex_slam {
namespace sim {
namespace {

// Drives `length` metres straight along x in `steps` equal steps; returns the final odometry.
Pose2 DriveStraight(const OdometryNoise& noise, std::uint64_t seed, double length, int steps) {
  DriftingOdometry odometry(noise, seed);
  for (int i = 0; i <= steps; ++i) odometry.Update(Pose2(length * i / steps, 0.0, 0.0));
  return odometry.pose();
}

struct Moments {
  double mean = 0.0, stddev = 0.0;
};

template <class F>
Moments Sample(int n, F f) {
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = f(i);
    sum += v;
    sum_sq += v * v;
  }
  Moments m;
  m.mean = sum / n;
  m.stddev = std::sqrt(std::max(0.0, sum_sq / n - m.mean * m.mean));
  return m;
}

TEST(OdometryModelTest, WithoutNoiseItReportsTheTrueMotion) {
  DriftingOdometry odometry(OdometryNoise(), 1, Pose2(1.0, 2.0, 0.5));
  const Pose2 truth0(-3.0, 4.0, 1.0);
  EXPECT_NEAR(odometry.Update(truth0).x, 1.0, 1e-12);  // the first pose maps to the start
  const Pose2 truth1 = truth0 * Pose2(0.3, 0.1, 0.2);
  const Pose2 odom1 = odometry.Update(truth1);
  const Pose2 expected = Pose2(1.0, 2.0, 0.5) * Pose2(0.3, 0.1, 0.2);
  EXPECT_NEAR(odom1.x, expected.x, 1e-12);
  EXPECT_NEAR(odom1.y, expected.y, 1e-12);
  EXPECT_NEAR(odom1.theta, expected.theta, 1e-12);
}

TEST(OdometryModelTest, DeterministicForASeed) {
  const OdometryNoise noise = OdometryNoise::Typical();
  const Pose2 a = DriveStraight(noise, 5, 3.0, 30), b = DriveStraight(noise, 5, 3.0, 30);
  const Pose2 c = DriveStraight(noise, 6, 3.0, 30);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_NE(a.x, c.x);
}

TEST(OdometryModelTest, DistanceErrorIsARandomWalkPlusTheScaleError) {
  OdometryNoise noise;
  noise.translation_stddev = 0.02;
  noise.translation_scale_error = 0.01;
  const double length = 9.0;
  const int runs = 4000;
  for (int steps : {30, 300}) {  // the same drift whatever the sampling rate
    const Moments m = Sample(runs, [&](int i) {
      return DriveStraight(noise, 100 + i, length, steps).x - length;
    });
    EXPECT_NEAR(m.mean, 0.01 * length, 0.003) << steps << " steps";
    EXPECT_NEAR(m.stddev, 0.02 * std::sqrt(length), 0.05 * 0.02 * std::sqrt(length))
        << steps << " steps";
  }
}

TEST(OdometryModelTest, HeadingDriftsWithDistanceAndWithTurning) {
  OdometryNoise noise;
  noise.rotation_stddev_per_distance = 0.01;
  const double length = 4.0;
  const Moments driven = Sample(4000, [&](int i) {
    return DriveStraight(noise, 7000 + i, length, 40).theta;
  });
  EXPECT_NEAR(driven.mean, 0.0, 0.002);
  EXPECT_NEAR(driven.stddev, 0.01 * std::sqrt(length), 0.001);

  OdometryNoise turning;
  turning.rotation_stddev = 0.02;
  turning.rotation_scale_error = 0.05;
  const double turn = 3.0;  // rad, in place, in 30 steps
  const Moments turned = Sample(4000, [&](int i) {
    DriftingOdometry odometry(turning, 9000 + i);
    for (int k = 0; k <= 30; ++k) odometry.Update(Pose2(0.0, 0.0, turn * k / 30));
    return NormalizeAngle(odometry.pose().theta - turn);
  });
  EXPECT_NEAR(turned.mean, 0.05 * turn, 0.002);
  EXPECT_NEAR(turned.stddev, 0.02 * std::sqrt(turn), 0.002);
}

TEST(OdometryModelTest, ValidateNamesTheBadParameters) {
  OdometryNoise noise;
  EXPECT_TRUE(noise.Validate().empty());
  EXPECT_TRUE(OdometryNoise::Typical().Validate().empty());
  noise.translation_stddev = -1.0;
  noise.rotation_scale_error = 0.9;
  const std::vector<std::string> errors = noise.Validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("odom_translation_stddev"), std::string::npos);
  EXPECT_NE(errors[1].find("odom_rotation_scale_error"), std::string::npos);
  EXPECT_THROW(DriftingOdometry(noise, 1), std::invalid_argument);
  noise = OdometryNoise();
  noise.rotation_stddev = std::nan("");
  EXPECT_EQ(noise.Validate().size(), 1u);
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
