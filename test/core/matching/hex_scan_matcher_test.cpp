#include "hex_slam/matching/hex_scan_matcher.h"

#include <cmath>
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "hex_slam/map/hex_interpolation.h"
#include "../test_maps.h"

namespace hex_slam {
namespace {

using testing_util::MapOfTestRoom;
using testing_util::ScanPoints;

constexpr double kDeg = M_PI / 180.0;

std::vector<Eigen::Vector3d> ToCube(const std::vector<Eigen::Vector2d>& points) {
  std::vector<Eigen::Vector3d> cube;
  for (const auto& p : points) cube.push_back(CartesianToCube(p.x(), p.y()));
  return cube;
}

class HexScanMatcherTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    maps_ = new MapPyramid<HexLattice>(MapOfTestRoom<HexLattice>(0.05));
  }
  static void TearDownTestSuite() { delete maps_; }
  static MapPyramid<HexLattice>* maps_;
};
MapPyramid<HexLattice>* HexScanMatcherTest::maps_ = nullptr;

TEST_F(HexScanMatcherTest, LagrangeStepEqualsReducedThreeDofStep) {
  // MATH.md §6: the 5×5 KKT step is the reduced (x, y, θ) Gauss–Newton step mapped to cube space.
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  const Eigen::Matrix<double, 4, 3> a = CubePoseJacobian();
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 truth(u(rng) * 5, u(rng) * 5, u(rng) * 3);
    const auto scan = ToCube(ScanPoints(world, truth, lidar, &rng));
    const Pose2 start(truth.x + u(rng), truth.y + u(rng), truth.theta + u(rng) * 0.3);
    HexNormalEquations eq;
    LinearizeHex(maps_->level(0), scan, CubeStateFromPose(start), &eq);
    Eigen::Vector4d lagrange;
    ASSERT_TRUE(SolveLagrangeStep(eq.hessian, eq.gradient, &lagrange));
    // The 5×5 system itself, solved as it is written.
    Eigen::Matrix<double, 5, 5> kkt = Eigen::Matrix<double, 5, 5>::Zero();
    kkt.topLeftCorner<4, 4>() = eq.hessian;
    kkt(0, 4) = kkt(1, 4) = kkt(2, 4) = 0.5;
    kkt(4, 0) = kkt(4, 1) = kkt(4, 2) = 1.0;
    Eigen::Matrix<double, 5, 1> rhs;
    rhs << eq.gradient, 0.0;
    const Eigen::Matrix<double, 5, 1> full = kkt.fullPivLu().solve(rhs);
    EXPECT_NEAR((full.head<4>() - lagrange).norm(), 0.0, 1e-9 * (1.0 + lagrange.norm()));
    const Eigen::Matrix3d h_reduced = a.transpose() * eq.hessian * a;
    const Eigen::Vector3d reduced = h_reduced.ldlt().solve(a.transpose() * eq.gradient);
    EXPECT_NEAR((a * reduced - lagrange).norm(), 0.0, 1e-9 * (1.0 + lagrange.norm()));
    EXPECT_NEAR(lagrange.head<3>().sum(), 0.0, 1e-12);
  }
}

TEST_F(HexScanMatcherTest, LinearizedGradientMatchesFiniteDifferencesOfTheCost) {
  // b = Σ Jᵀr, so the cost's derivative along any tangent direction v is -2·bᵀv.
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  const Eigen::Matrix<double, 4, 3> a = CubePoseJacobian();
  const double h = 1e-7;
  for (int trial = 0; trial < 20; ++trial) {
    const auto scan = ToCube(ScanPoints(world, Pose2(u(rng), u(rng), u(rng)), lidar, &rng));
    const Eigen::Vector4d xi = CubeStateFromPose(Pose2(u(rng), u(rng), u(rng)));
    HexNormalEquations eq, plus, minus;
    LinearizeHex(maps_->level(0), scan, xi, &eq);
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector4d v = a.col(axis);
      LinearizeHex(maps_->level(0), scan, xi + h * v, &plus);
      LinearizeHex(maps_->level(0), scan, xi - h * v, &minus);
      const double fd = (plus.cost - minus.cost) / (2 * h);
      EXPECT_NEAR(-2.0 * eq.gradient.dot(v), fd, 1e-3 * (1.0 + std::abs(fd)));
    }
  }
}

// MATH.md §6's normal equations written out point by point in metres: J = (g, g·∂S/∂ψ) with the
// in-plane gradient g per metre and ∂S/∂ψ from CubeRotationDerivative, r = 1 - M.
HexNormalEquations ReferenceNormalEquations(const HexGrid& grid,
                                            const std::vector<Eigen::Vector3d>& scan,
                                            const Eigen::Vector4d& xi, bool subcell) {
  HexNormalEquations eq;
  for (const Eigen::Vector3d& s : scan) {
    const Eigen::Vector3d at = CubeRotation(xi[3]) * s + xi.head<3>();
    const HexSample m = subcell ? InterpolateHexSubcell(grid, at) : InterpolateHex(grid, at);
    Eigen::Vector4d j;
    j << m.gradient, m.gradient.dot(CubeRotationDerivative(s, xi[3]));
    const double r = 1.0 - m.value;
    eq.hessian += j * j.transpose();
    eq.gradient += j * r;
    eq.cost += r * r;
    eq.sum_value += m.value;
  }
  eq.count = static_cast<int>(scan.size());
  return eq;
}

TEST_F(HexScanMatcherTest, LinearizationEqualsThePointByPointNormalEquations) {
  // LinearizeHex reads the map in blocks, in lattice units and partials, and rebuilds H from six
  // sums: none of which may change what it computes.
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (bool subcell : {false, true}) {
    for (int level = 0; level < maps_->size(); ++level) {
      for (int trial = 0; trial < 5; ++trial) {
        const Pose2 truth(u(rng) * 10, u(rng) * 10, u(rng) * 10);
        const auto scan = ToCube(ScanPoints(world, truth, lidar, &rng));
        const Eigen::Vector4d xi =
            CubeStateFromPose(Pose2(truth.x + u(rng), truth.y + u(rng), truth.theta + u(rng)));
        HexNormalEquations eq;
        LinearizeHex(maps_->level(level), scan, xi, &eq, subcell);
        const HexNormalEquations ref = ReferenceNormalEquations(maps_->level(level), scan, xi,
                                                                subcell);
        const double scale = 1e-9 * (1.0 + ref.hessian.norm());
        EXPECT_NEAR((eq.hessian - ref.hessian).norm(), 0.0, scale) << subcell << " " << level;
        EXPECT_NEAR((eq.gradient - ref.gradient).norm(), 0.0, 1e-9 * (1.0 + ref.gradient.norm()));
        EXPECT_NEAR(eq.cost, ref.cost, 1e-9 * (1.0 + ref.cost));
        EXPECT_NEAR(eq.sum_value, ref.sum_value, 1e-9 * (1.0 + ref.sum_value));
        EXPECT_EQ(eq.count, ref.count);
      }
    }
  }
}

TEST_F(HexScanMatcherTest, RecoversAKnownOffsetToUnderACentimetre) {
  // The bar: from 0.2 m and 5° off, back to < 1 cm and < 0.2°, over many poses and
  // offset directions.
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 1080;
  lidar.range_noise_stddev = 0.0;
  const HexScanMatcher matcher{ScanMatcherOptions()};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(-0.5, 0.5), heading(-M_PI, M_PI);
  for (int trial = 0; trial < 24; ++trial) {
    const Pose2 truth(pos(rng), pos(rng), heading(rng));
    const auto points = ScanPoints(world, truth, lidar, &rng);
    const double dir = heading(rng);
    const double sign = trial % 2 ? 1.0 : -1.0;
    const Pose2 guess(truth.x + 0.2 * std::cos(dir), truth.y + 0.2 * std::sin(dir),
                      truth.theta + sign * 5.0 * kDeg);
    const MatchResult result = matcher.Match(*maps_, points, guess);
    EXPECT_LT((result.pose.translation() - truth.translation()).norm(), 0.01)
        << "trial " << trial;
    EXPECT_LT(std::abs(NormalizeAngle(result.pose.theta - truth.theta)), 0.2 * kDeg)
        << "trial " << trial;
    EXPECT_GT(result.mean_occupancy, 0.7);
  }
}

// Matches of noisy scans from 0.1 m / 3° off, with `options`: the poses and the per-level reports.
std::vector<MatchResult> MatchesFromOffsets(const MapPyramid<HexLattice>& maps,
                                            const ScanMatcherOptions& options) {
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  const HexScanMatcher matcher(options);
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> pos(-0.5, 0.5), heading(-M_PI, M_PI);
  std::vector<MatchResult> results;
  for (int trial = 0; trial < 20; ++trial) {
    const Pose2 truth(pos(rng), pos(rng), heading(rng));
    const auto points = ScanPoints(world, truth, lidar, &rng);
    const double dir = heading(rng);
    const Pose2 guess(truth.x + 0.1 * std::cos(dir), truth.y + 0.1 * std::sin(dir),
                      truth.theta + (trial % 2 ? 3.0 : -3.0) * kDeg);
    results.push_back(matcher.Match(maps, points, guess));
  }
  return results;
}

TEST_F(HexScanMatcherTest, AConvergedStepIsTakenWithoutAnotherPassUnlessVerified) {
  ScanMatcherOptions verified;
  verified.verify_converged_step = true;
  const std::vector<MatchResult> fast = MatchesFromOffsets(*maps_, ScanMatcherOptions());
  const std::vector<MatchResult> slow = MatchesFromOffsets(*maps_, verified);
  int fast_passes = 0, slow_passes = 0;
  for (std::size_t i = 0; i < fast.size(); ++i) {
    for (int level = 0; level < maps_->size(); ++level) {
      fast_passes += fast[i].levels[level].linearizations;
      slow_passes += slow[i].levels[level].linearizations;
      // Verified, every step was evaluated after it was taken, and the first pass came before.
      EXPECT_GE(slow[i].levels[level].linearizations, slow[i].levels[level].iterations + 1);
    }
    // The step left unchecked is below the tolerances: the poses agree to a millimetre.
    EXPECT_LT((fast[i].pose.translation() - slow[i].pose.translation()).norm(), 1e-3) << i;
    EXPECT_LT(std::abs(NormalizeAngle(fast[i].pose.theta - slow[i].pose.theta)), 0.05 * kDeg);
  }
  EXPECT_LT(fast_passes, 0.85 * slow_passes);
}

TEST_F(HexScanMatcherTest, AnAngleToleranceFromTheMeanRangeSavesIterationsNotPrecision) {
  // In the test room (mean range about 3 m) the finest level's angle tolerance stays near the
  // fixed 0.3 mrad; the coarse levels', like their translation tolerance, grow with their cells.
  ScanMatcherOptions fixed_tolerance;
  fixed_tolerance.angle_tolerance_from_range = false;
  const std::vector<MatchResult> ranged = MatchesFromOffsets(*maps_, ScanMatcherOptions());
  const std::vector<MatchResult> fixed = MatchesFromOffsets(*maps_, fixed_tolerance);
  int ranged_iterations = 0, fixed_iterations = 0;  // on the coarse levels
  for (std::size_t i = 0; i < ranged.size(); ++i) {
    for (int level = 1; level < maps_->size(); ++level) {
      ranged_iterations += ranged[i].levels[level].iterations;
      fixed_iterations += fixed[i].levels[level].iterations;
    }
    EXPECT_LT((ranged[i].pose.translation() - fixed[i].pose.translation()).norm(), 1e-3) << i;
    EXPECT_LT(std::abs(NormalizeAngle(ranged[i].pose.theta - fixed[i].pose.theta)), 0.05 * kDeg);
  }
  EXPECT_LT(ranged_iterations, fixed_iterations);
}

TEST_F(HexScanMatcherTest, ACoarsestMoveWithinItsCellsBiasIsDroppedAFarOneIsKept) {
  // From the truth the coarsest level (plain map, 0.2 m cells) only drifts to its own biased
  // optimum: that move is dropped and the finer levels start from the guess. From 0.2 m off it
  // moves the pose a long way: that move is kept. With the default 0 every move is kept.
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.range_noise_stddev = 0.0;
  ScanMatcherOptions drop_small, keep_all;
  drop_small.coarsest_min_move_cells = 0.25;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-0.5, 0.5), heading(-M_PI, M_PI);
  const int coarsest = maps_->size() - 1;
  int dropped_at_truth = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Pose2 truth(pos(rng), pos(rng), heading(rng));
    const auto points = ScanPoints(world, truth, lidar, &rng);
    const MatchResult at_truth = HexScanMatcher(drop_small).Match(*maps_, points, truth);
    dropped_at_truth += at_truth.levels[coarsest].move_dropped;
    EXPECT_LT((at_truth.pose.translation() - truth.translation()).norm(), 0.01);
    const Pose2 far(truth.x + 0.2, truth.y - 0.1, truth.theta + 5.0 * kDeg);
    const MatchResult from_far = HexScanMatcher(drop_small).Match(*maps_, points, far);
    EXPECT_FALSE(from_far.levels[coarsest].move_dropped) << trial;
    EXPECT_LT((from_far.pose.translation() - truth.translation()).norm(), 0.01) << trial;
    const MatchResult kept = HexScanMatcher(keep_all).Match(*maps_, points, truth);
    EXPECT_FALSE(kept.levels[coarsest].move_dropped);
  }
  EXPECT_GE(dropped_at_truth, 8);
}

TEST_F(HexScanMatcherTest, CovarianceIsSmallWhereTheRoomConstrainsThePose) {
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.range_noise_stddev = 0.0;
  std::mt19937_64 rng(4);
  const auto points = ScanPoints(world, Pose2(), lidar, &rng);
  const MatchResult result = HexScanMatcher(ScanMatcherOptions()).Match(*maps_, points, Pose2());
  EXPECT_LT(std::sqrt(result.covariance(0, 0)), 0.01);
  EXPECT_LT(std::sqrt(result.covariance(1, 1)), 0.01);
  EXPECT_LT(std::sqrt(result.covariance(2, 2)), 0.01);
  EXPECT_GT(result.covariance.determinant(), 0.0);
}

TEST(HexScanMatcherSolveTest, SingularSystemIsReportedNotSolved) {
  Eigen::Vector4d step;
  EXPECT_FALSE(SolveLagrangeStep(Eigen::Matrix4d::Zero(), Eigen::Vector4d::Zero(), &step));
}

TEST(HexScanMatcherEmptyMapTest, UnknownMapLeavesTheGuessAlone) {
  MapPyramid<HexLattice> empty(0.05, 3, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                               GridGrowthPolicy(),
                               Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
  const std::vector<Eigen::Vector2d> points = {{1.0, 0.0}, {0.0, 1.0}, {-1.0, 0.5}};
  const Pose2 guess(0.3, -0.2, 0.1);
  const MatchResult result = HexScanMatcher(ScanMatcherOptions()).Match(empty, points, guess);
  EXPECT_NEAR(result.pose.x, guess.x, 1e-12);
  EXPECT_NEAR(result.pose.y, guess.y, 1e-12);
  EXPECT_NEAR(result.pose.theta, guess.theta, 1e-12);
}

TEST(HexScanMatcherTestBias, SubcellOffsetsRemoveTheWallsCellBias) {
  // Matches started at the truth stay where the map's walls pull them: without sub-cell offsets
  // that is each wall's cell centre (up to half a cell off); with them, where the walls were seen.
  ScanMatcherOptions plain;
  plain.subcell_offsets = false;
  const double biased = testing_util::StaticBiasInBiasedRoom<HexLattice, HexScanMatcher>(0.1, plain);
  const double subcell = testing_util::StaticBiasInBiasedRoom<HexLattice, HexScanMatcher>(0.1, ScanMatcherOptions());
  EXPECT_GT(biased, 0.01);
  EXPECT_LT(subcell, 0.4 * biased);
  EXPECT_LT(subcell, 0.006);
}

}  // namespace
}  // namespace hex_slam
