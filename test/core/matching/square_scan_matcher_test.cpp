#include "hex_slam/matching/square_scan_matcher.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "../test_maps.h"

namespace hex_slam {
namespace {

using testing_util::MapOfTestRoom;
using testing_util::ScanPoints;

constexpr double kDeg = M_PI / 180.0;

TEST(SquareScanMatcherTest, LinearizedGradientMatchesFiniteDifferencesOfTheCost) {
  const MapPyramid<SquareLattice> maps = MapOfTestRoom<SquareLattice>(0.05);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  const double h = 1e-7;
  for (int trial = 0; trial < 20; ++trial) {
    const auto scan = ScanPoints(world, Pose2(u(rng), u(rng), u(rng)), lidar, &rng);
    const Eigen::Vector3d pose(u(rng), u(rng), u(rng));
    SquareNormalEquations eq, plus, minus;
    LinearizeSquare(maps.level(0), scan, pose, &eq);
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d v = Eigen::Vector3d::Unit(axis);
      LinearizeSquare(maps.level(0), scan, pose + h * v, &plus);
      LinearizeSquare(maps.level(0), scan, pose - h * v, &minus);
      const double fd = (plus.cost - minus.cost) / (2 * h);
      EXPECT_NEAR(-2.0 * eq.gradient.dot(v), fd, 1e-3 * (1.0 + std::abs(fd)));
    }
  }
}

TEST(SquareScanMatcherTest, RecoversAKnownOffsetToUnderACentimetre) {
  // The square side with the hex test's cell area (0.05 m hex spacing).
  const double side = 0.05 * std::sqrt(0.5 * std::sqrt(3.0));
  const MapPyramid<SquareLattice> maps = MapOfTestRoom<SquareLattice>(side);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 1080;
  lidar.range_noise_stddev = 0.0;
  const SquareScanMatcher matcher{ScanMatcherOptions()};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(-0.5, 0.5), heading(-M_PI, M_PI);
  for (int trial = 0; trial < 24; ++trial) {
    const Pose2 truth(pos(rng), pos(rng), heading(rng));
    const auto points = ScanPoints(world, truth, lidar, &rng);
    const double dir = heading(rng);
    const double sign = trial % 2 ? 1.0 : -1.0;
    const Pose2 guess(truth.x + 0.2 * std::cos(dir), truth.y + 0.2 * std::sin(dir),
                      truth.theta + sign * 5.0 * kDeg);
    const MatchResult result = matcher.Match(maps, points, guess);
    EXPECT_LT((result.pose.translation() - truth.translation()).norm(), 0.01)
        << "trial " << trial;
    EXPECT_LT(std::abs(NormalizeAngle(result.pose.theta - truth.theta)), 0.2 * kDeg)
        << "trial " << trial;
  }
}

TEST(SquareScanMatcherTestBias, SubcellOffsetsRemoveTheWallsCellBias) {
  // Matches started at the truth stay where the map's walls pull them: without sub-cell offsets
  // that is each wall's cell centre (up to half a cell off); with them, where the walls were seen.
  ScanMatcherOptions plain;
  plain.subcell_offsets = false;
  const double biased = testing_util::StaticBiasInBiasedRoom<SquareLattice, SquareScanMatcher>(0.1, plain);
  const double subcell = testing_util::StaticBiasInBiasedRoom<SquareLattice, SquareScanMatcher>(0.1, ScanMatcherOptions());
  EXPECT_GT(biased, 0.01);
  EXPECT_LT(subcell, 0.4 * biased);
  EXPECT_LT(subcell, 0.006);
}

}  // namespace
}  // namespace hex_slam
