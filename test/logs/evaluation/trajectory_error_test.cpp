#include "hex_slam/logs/evaluation/trajectory_error.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace hex_slam {
namespace logs {
namespace {

TEST(TrajectoryErrorTest, AlignmentRecoversAKnownTransformOverManySeeds) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> coord(-20.0, 20.0), angle(-M_PI, M_PI);
    const Pose2 truth(coord(rng), coord(rng), angle(rng));
    std::vector<Eigen::Vector2d> from, to;
    for (int i = 0; i < 50; ++i) {
      from.emplace_back(coord(rng), coord(rng));
      to.push_back(truth * from.back());
    }
    const Pose2 found = AlignPoints(from, to);
    EXPECT_NEAR(found.x, truth.x, 1e-9) << "seed " << seed;
    EXPECT_NEAR(found.y, truth.y, 1e-9) << "seed " << seed;
    EXPECT_NEAR(NormalizeAngle(found.theta - truth.theta), 0.0, 1e-9) << "seed " << seed;
  }
}

TEST(TrajectoryErrorTest, AlignmentIsTheLeastSquaresFitUnderNoise) {
  // Symmetric noise on a square: the fit is exact for the centroid and the heading.
  const std::vector<Eigen::Vector2d> from = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Pose2 truth(2.0, -1.0, 0.5);
  std::vector<Eigen::Vector2d> to;
  const double e = 0.1;
  const std::vector<Eigen::Vector2d> noise = {{e, 0}, {-e, 0}, {e, 0}, {-e, 0}};
  for (std::size_t i = 0; i < from.size(); ++i) to.push_back(truth * from[i] + noise[i]);
  const Pose2 found = AlignPoints(from, to);
  const Eigen::Vector2d centroid = truth * Eigen::Vector2d(0.5, 0.5);
  EXPECT_NEAR((found * Eigen::Vector2d(0.5, 0.5) - centroid).norm(), 0.0, 1e-12);
  // Degenerate inputs: identity for one point, translation for coincident ones.
  EXPECT_EQ(AlignPoints({{1, 1}}, {{3, 3}}).x, 0.0);
  const Pose2 shift = AlignPoints({{1, 1}, {1, 1}}, {{3, 2}, {3, 2}});
  EXPECT_NEAR(shift.x, 2.0, 1e-12);
  EXPECT_NEAR(shift.y, 1.0, 1e-12);
  EXPECT_EQ(shift.theta, 0.0);
}

std::vector<io::StampedPose> Circle(int n, double dt) {
  std::vector<io::StampedPose> poses;
  for (int i = 0; i < n; ++i) {
    const double a = 0.05 * i;
    poses.push_back({i * dt, Pose2(5 * std::cos(a), 5 * std::sin(a), a + M_PI / 2)});
  }
  return poses;
}

TEST(TrajectoryErrorTest, ARigidlyMovedCopyHasZeroAteAndZeroRpe) {
  const std::vector<io::StampedPose> truth = Circle(200, 0.1);
  const Pose2 offset(3.0, -2.0, 1.0);
  std::vector<io::StampedPose> estimate = truth;
  for (io::StampedPose& p : estimate) p.pose = offset * p.pose;
  const TrajectoryErrorReport r = EvaluateTrajectory(estimate, truth, TrajectoryErrorOptions());
  EXPECT_EQ(r.matched, 200);
  EXPECT_NEAR(r.ate_translation.rmse, 0.0, 1e-9);
  EXPECT_NEAR(r.ate_rotation.rmse, 0.0, 1e-7);
  EXPECT_NEAR(r.rpe_translation.rmse, 0.0, 1e-9);
  EXPECT_EQ(r.rpe_translation.count, 190);  // pairs 1 s (10 poses) apart
  const Pose2 undo = r.alignment * offset;
  EXPECT_NEAR(undo.x, 0.0, 1e-9);
  EXPECT_NEAR(NormalizeAngle(undo.theta), 0.0, 1e-9);
}

TEST(TrajectoryErrorTest, AJumpShowsInAteEverywhereAndInRpeOnlyAcrossIt) {
  const std::vector<io::StampedPose> truth = Circle(200, 0.1);
  std::vector<io::StampedPose> estimate = truth;
  // From pose 100 on, everything is 0.5 m off in x: a jump no rigid motion removes.
  for (std::size_t i = 100; i < estimate.size(); ++i) estimate[i].pose.x += 0.5;
  const TrajectoryErrorReport r = EvaluateTrajectory(estimate, truth, TrajectoryErrorOptions());
  EXPECT_GT(r.ate_translation.rmse, 0.1);
  EXPECT_NEAR(r.rpe_translation.median, 0.0, 1e-9);  // most pairs lie on one side of it
  EXPECT_NEAR(r.rpe_translation.max, 0.5, 1e-9);
  EXPECT_NEAR(r.rpe_rotation.max, 0.0, 1e-7);
}

TEST(TrajectoryErrorTest, PosesWithoutGroundTruthAreNotMatched) {
  const std::vector<io::StampedPose> truth = Circle(10, 1.0);
  std::vector<io::StampedPose> estimate = {{0.5, Pose2()}, {3.0, Pose2()}, {50.0, Pose2()}};
  const TrajectoryErrorReport r = EvaluateTrajectory(estimate, truth, TrajectoryErrorOptions());
  EXPECT_EQ(r.poses, 3);
  EXPECT_EQ(r.matched, 1);  // 0.5 s lies between poses 1 s apart: more than max_gap
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
