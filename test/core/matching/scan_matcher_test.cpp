#include "hex_slam/matching/scan_matcher.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/matching/hex_scan_matcher.h"
#include "hex_slam/matching/square_scan_matcher.h"
#include "../test_maps.h"

namespace hex_slam {
namespace {

TEST(ScanMatcherTest, DecimationKeepsPointsAtLeastTheSpacingFromTheLastKept) {
  const std::vector<Eigen::Vector2d> points = {{0.0, 0.0}, {0.05, 0.0}, {0.09, 0.0}, {0.11, 0.0},
                                               {0.15, 0.0}, {0.3, 0.0}};
  std::vector<Eigen::Vector2d> kept;
  DecimateScan(points, 0.1, &kept);
  // 0.05 and 0.09 are within 0.1 of 0; 0.11 is not; 0.15 is within 0.1 of 0.11.
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[0], points[0]);
  EXPECT_EQ(kept[1], points[3]);
  EXPECT_EQ(kept[2], points[5]);
  DecimateScan(points, 0.0, &kept);
  EXPECT_EQ(kept, points);
  std::vector<Eigen::Vector2d> visited;
  ForEachKeptEndpoint(points, 0.1, [&visited](const Eigen::Vector2d& p) { visited.push_back(p); });
  DecimateScan(points, 0.1, &kept);
  EXPECT_EQ(visited, kept);
  DecimateScan({}, 0.1, &kept);
  EXPECT_TRUE(kept.empty());
}

TEST(ScanMatcherTest, EndpointMoveBoundIsTranslationPlusTurnTimesReach) {
  const std::vector<Eigen::Vector2d> points = {{3.0, 4.0}, {-1.0, 0.5}};
  EXPECT_DOUBLE_EQ(Reach(points), 5.0);
  EXPECT_DOUBLE_EQ(Reach({}), 0.0);
  const Pose2 from(1.0, 2.0, 0.1), to(1.3, 2.4, 0.3);
  EXPECT_DOUBLE_EQ(EndpointMoveBound(from, to, 5.0), 0.5 + 0.2 * 5.0);
  // It bounds every endpoint's actual move.
  for (const Eigen::Vector2d& p : points) {
    EXPECT_LE(((to * p) - (from * p)).norm(), EndpointMoveBound(from, to, Reach(points)) + 1e-12);
  }
  // Across ±π the turn is the short way round.
  EXPECT_NEAR(EndpointMoveBound(Pose2(0, 0, M_PI - 0.01), Pose2(0, 0, -M_PI + 0.01), 1.0), 0.02,
              1e-12);
}

TEST(ScanMatcherTest, HectorsMethodTurnsOffWhatHexSlamAdds) {
  ScanMatcherOptions options;
  options.max_iterations_fine = 7;
  options.coarsest_min_move_cells = 0.25;
  UseHectorsMethod(&options);
  EXPECT_FALSE(options.subcell_offsets);
  EXPECT_TRUE(options.verify_converged_step);
  EXPECT_FALSE(options.angle_tolerance_from_range);
  EXPECT_EQ(options.coarsest_min_move_cells, 0.0);
  EXPECT_EQ(options.max_iterations_fine, 7);  // the rest is kept
  EXPECT_TRUE(options.Validate().empty());
  options.coarsest_min_move_cells = -1.0;
  ASSERT_EQ(options.Validate().size(), 1u);
  EXPECT_NE(options.Validate()[0].find("scan_match_coarsest_min_move_cells"), std::string::npos);
}

TEST(ScanMatcherTest, AngleToleranceMovesTheMeanEndpointAsFarAsTheTranslationTolerance) {
  ScanMatcherOptions options;
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.002, 4.0), 0.0005);
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.004, 4.0), 0.001);  // a coarser level
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.002, 0.0), options.angle_tolerance);  // no points
  options.angle_tolerance_from_range = false;
  EXPECT_DOUBLE_EQ(options.LevelAngleTolerance(0.004, 4.0), options.angle_tolerance);
  EXPECT_DOUBLE_EQ(MeanRange({{3.0, 4.0}, {0.0, 1.0}}), 3.0);
  EXPECT_DOUBLE_EQ(MeanRange({}), 0.0);
}

TEST(ScanMatcherTest, RobustKernelWeightIsTheDerivativeOfItsCost) {
  const RobustKernel off(0.0), cauchy(0.3);
  EXPECT_FALSE(off.enabled());
  EXPECT_TRUE(cauchy.enabled());
  for (double r : {0.0, 0.05, 0.2, 0.5, 0.9, 1.0}) {
    EXPECT_EQ(off.Weight(r), 1.0);
    EXPECT_DOUBLE_EQ(off.Cost(r), r * r);
    // IRLS: the weight is ρ'(r) / 2r, checked against a central difference of ρ.
    constexpr double h = 1e-6;
    const double derivative = (cauchy.Cost(r + h) - cauchy.Cost(r - h)) / (2.0 * h);
    EXPECT_NEAR(derivative, 2.0 * r * cauchy.Weight(r), 1e-6) << r;
    EXPECT_LE(cauchy.Cost(r), r * r + 1e-15);  // never costs more than least squares
  }
  EXPECT_NEAR(cauchy.Weight(0.3), 0.5, 1e-12);  // the scale is where the weight halves
  EXPECT_LT(cauchy.Weight(1.0), 0.1);
  ScanMatcherOptions options;
  options.robust_loss_scale = -0.1;
  ASSERT_EQ(options.Validate().size(), 1u);
  EXPECT_NE(options.Validate()[0].find("scan_match_robust_loss_scale"), std::string::npos);
  options.robust_loss_scale = 1e-9;  // below kMinRobustLossScale: every endpoint weighs nothing
  ASSERT_EQ(options.Validate().size(), 1u);
  options.robust_loss_scale = 0.0;
  EXPECT_TRUE(options.Validate().empty());
  options.robust_loss_scale = 0.3;
  UseHectorsMethod(&options);
  EXPECT_EQ(options.robust_loss_scale, 0.0);  // hector's method is plain least squares
}

// Both lattices' matchers, for tests of what they share.
template <class L, class M>
struct LatticeAndMatcher {
  using Lattice = L;
  using Matcher = M;
};
template <class T>
class RobustMatchTest : public ::testing::Test {};
using Matchers = ::testing::Types<LatticeAndMatcher<HexLattice, HexScanMatcher>,
                                  LatticeAndMatcher<SquareLattice, SquareScanMatcher>>;
TYPED_TEST_SUITE(RobustMatchTest, Matchers);

// A scan of the test room of which every third return comes from a phantom: the room as seen
// from 5 cm and 0.02 rad away, reported as if from the robot (returns that move with the robot
// and lie near walls, where the map has a slope to pull them along). Plain least squares settles
// between the two rooms; the robust loss lets the phantom go. The oracle is the true pose.
TYPED_TEST(RobustMatchTest, OutliersThatMoveWithTheRobotLoseTheirWeight) {
  using Lattice = typename TypeParam::Lattice;
  using Matcher = typename TypeParam::Matcher;
  const double spacing = 0.05;
  const MapPyramid<Lattice> maps = testing_util::MapOfTestRoom<Lattice>(spacing);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 720;
  lidar.range_noise_stddev = 0.005;
  const Pose2 phantom_offset(0.05, -0.035, 0.02);
  constexpr int kPhantomEvery = 3;  // every third beam comes from the phantom
  std::mt19937_64 rng(7);
  double plain_error = 0.0, robust_error = 0.0;
  const std::vector<Pose2> poses = {Pose2(0.3, 0.2, 0.1), Pose2(-2.0, 0.5, 1.2),
                                    Pose2(2.8, -0.8, -0.7)};
  for (const Pose2& room_pose : poses) {
    const Pose2 truth = testing_util::GenericPlacement() * room_pose;
    const std::vector<Eigen::Vector2d> real = testing_util::ScanPoints(world, truth, lidar, &rng);
    const std::vector<Eigen::Vector2d> ghost =
        testing_util::ScanPoints(world, truth * phantom_offset, lidar, &rng);
    std::vector<Eigen::Vector2d> points;
    for (std::size_t i = 0; i < real.size(); ++i) {
      if (i % kPhantomEvery != 0) points.push_back(real[i]);
    }
    for (std::size_t i = 0; i < ghost.size(); i += kPhantomEvery) {
      points.push_back(ghost[i]);  // as if seen from the robot: the room displaced
    }
    const Pose2 guess = truth * Pose2(0.03, -0.02, 0.01);
    ScanMatcherOptions options;
    options.robust_loss_scale = 0.0;
    const Pose2 plain = Matcher(options).Match(maps, points, guess).pose;
    options.robust_loss_scale = 0.3;
    const Pose2 robust = Matcher(options).Match(maps, points, guess).pose;
    plain_error = std::max(plain_error, (plain.translation() - truth.translation()).norm());
    robust_error = std::max(robust_error, (robust.translation() - truth.translation()).norm());
    EXPECT_LT(std::abs(NormalizeAngle(robust.theta - truth.theta)), 0.01);
  }
  std::printf("phantom third: worst position error %.4f m plain, %.4f m robust\n", plain_error,
              robust_error);
  // Measured: 6.0 / 7.8 mm plain, 1.2 / 2.1 mm robust (hex / square).
  EXPECT_GT(plain_error, 0.005) << "the phantom must pull plain least squares off";
  EXPECT_LT(robust_error, 0.003);
  EXPECT_LT(robust_error, 0.5 * plain_error);
}

// Odometry's pull is a quadratic prior on the position beside the map: off (weight 0) it changes
// nothing; as its weight grows the matched position moves from where the map puts it to
// odometry's; odometry's heading is never held; and the Hessian reported is the map's alone
// (the oracle: the same matcher linearising the map at the result, with no iteration and no pull).
TYPED_TEST(RobustMatchTest, OdometrysPullHoldsThePositionNotTheHeadingAndLeavesTheMapsHessian) {
  using Lattice = typename TypeParam::Lattice;
  using Matcher = typename TypeParam::Matcher;
  const MapPyramid<Lattice> maps = testing_util::MapOfTestRoom<Lattice>(0.05);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 360;
  lidar.range_noise_stddev = 0.005;
  std::mt19937_64 rng(11);
  const Pose2 truth = testing_util::GenericPlacement() * Pose2(0.3, 0.2, 0.1);
  const std::vector<Eigen::Vector2d> points = testing_util::ScanPoints(world, truth, lidar, &rng);
  const Pose2 odometry = truth * Pose2(0.03, -0.02, 0.01);

  ScanMatcherOptions options;
  options.verify_converged_step = true;  // every level's equations at its final state
  options.odometry_translation_weight = 0.0;
  const Pose2 free = Matcher(options).Match(maps, points, odometry).pose;
  const Pose2 off = Matcher(options).Match(maps, points, odometry, GuessSource::kOdometry).pose;
  EXPECT_EQ(off.x, free.x);
  EXPECT_EQ(off.y, free.y);
  EXPECT_EQ(off.theta, free.theta);
  EXPECT_LT((free.translation() - truth.translation()).norm(), 0.005);

  double previous = (free.translation() - odometry.translation()).norm();
  for (const double weight : {3.0, 30.0, 300.0, 1e5}) {
    options.odometry_translation_weight = weight;
    const MatchResult pulled =
        Matcher(options).Match(maps, points, odometry, GuessSource::kOdometry);
    const double to_odometry = (pulled.pose.translation() - odometry.translation()).norm();
    EXPECT_LE(to_odometry, previous + 1e-4) << "weight " << weight;
    previous = to_odometry;

    ScanMatcherOptions linearise_only = options;
    linearise_only.max_iterations_coarse = 0;
    linearise_only.max_iterations_fine = 0;
    const MatchResult map_alone = Matcher(linearise_only).Match(maps, points, pulled.pose);
    EXPECT_LT((pulled.hessian - map_alone.hessian).norm(), 1e-9 * map_alone.hessian.norm())
        << "weight " << weight;
    EXPECT_NEAR(pulled.cost, map_alone.cost, 1e-9 * map_alone.cost + 1e-12);
  }
  EXPECT_LT(previous, 0.001);  // at 1e5 odometry's position holds

  // Odometry right in position but 0.02 rad off in heading: however hard the pull, the heading
  // is the map's.
  const Pose2 turned = truth * Pose2(0.0, 0.0, 0.02);
  const Pose2 held = Matcher(options).Match(maps, points, turned, GuessSource::kOdometry).pose;
  EXPECT_LT(std::abs(NormalizeAngle(held.theta - truth.theta)), 0.002);
  EXPECT_LT((held.translation() - truth.translation()).norm(), 0.001);
}

}  // namespace
}  // namespace hex_slam
