#include "hex_slam/matching/correlative_search.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"
#include "hex_slam/matching/precomputation_grid.h"
#include "hex_slam/matching/step_bounds.h"
#include "../test_maps.h"
#include "random_maps.h"

namespace hex_slam {
namespace {

using testing_util::GenericRoom;
using testing_util::MapOfTestRoom;
using testing_util::ScanPoints;

// Scans of the test room from random poses, each with a search centre off the truth by up to
// `linear` (m, along each axis) and `angular` (rad).
class RoomScans {
 public:
  struct Trial {
    Pose2 truth;
    std::vector<Eigen::Vector2d> points;
    Pose2 centre;
  };
  explicit RoomScans(std::uint64_t seed) : rng_(seed) {}
  Trial Next(double linear, double angular) {
    Trial t;
    t.truth = Pose2(0.5 * u_(rng_), 0.5 * u_(rng_), M_PI * u_(rng_));
    t.points = ScanPoints(world_, t.truth, lidar_, &rng_);
    t.centre = Pose2(t.truth.x + linear * u_(rng_), t.truth.y + linear * u_(rng_),
                     t.truth.theta + angular * u_(rng_));
    return t;
  }
  // A uniform number in [-1, 1) from the same stream.
  double Uniform() { return u_(rng_); }

 private:
  const sim::SegmentWorld world_ = GenericRoom();
  sim::LidarModel lidar_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> u_{-1.0, 1.0};
};

template <class T>
class CorrelativeSearchTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(CorrelativeSearchTest, Lattices);

TYPED_TEST(CorrelativeSearchTest, FindsThePoseFarOutsideGaussNewtonsBasin) {
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);  // 0.2 m cells
  RoomScans scans(1);
  CorrelativeSearchOptions options;
  for (int trial = 0; trial < 10; ++trial) {
    // Off by up to 0.3 m and 0.5 rad: several coarse cells and far beyond a few degrees.
    const auto [truth, points, centre] = scans.Next(0.3, 0.5);
    const CorrelativeResult found = SearchCorrelative(coarse, points, centre, options);
    const double step = options.step_cells * coarse.lattice().spacing();
    EXPECT_LT((found.pose.translation() - truth.translation()).norm(), 1.5 * step)
        << "trial " << trial;
    EXPECT_LT(std::abs(NormalizeAngle(found.pose.theta - truth.theta)), 0.05) << "trial " << trial;
    EXPECT_GT(found.candidates, 1000);
    EXPECT_GT(found.score, SearchCorrelative(coarse, points, centre,
                                             CorrelativeSearchOptions{0.0, 0.0, 0.5, 1.0})
                               .score);
  }
}

TYPED_TEST(CorrelativeSearchTest, ScoreAtAPoseIsTheSearchsScoreThereAndNoneBeatsTheBest) {
  // The large-step check compares two matches by CorrelativeScore: it must score a pose exactly
  // as the search did, and no pose of the window may score above the one the search returned.
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  RoomScans scans(2);
  CorrelativeSearchOptions options;
  options.linear_window = 0.2;
  options.angular_window = 0.1;
  for (int trial = 0; trial < 5; ++trial) {
    const auto [truth, points, centre] = scans.Next(0.2, 0.1);
    const CorrelativeResult found = SearchCorrelative(coarse, points, centre, options);
    EXPECT_DOUBLE_EQ(CorrelativeScore(coarse, points, found.pose, options), found.score);
    for (int k = 0; k < 50; ++k) {
      const Pose2 other(centre.x + 0.2 * scans.Uniform(), centre.y + 0.2 * scans.Uniform(),
                        centre.theta + 0.1 * scans.Uniform());
      // Off the search's grid a pose may fall between its samples: within the sampling's reach.
      EXPECT_LE(CorrelativeScore(coarse, points, other, options), found.score + 0.05)
          << "trial " << trial;
    }
  }
  EXPECT_EQ(CorrelativeScore(coarse, {}, Pose2(), options), 0.0);
}

// The exhaustive search the branch and bound must reproduce: every pose of the window the search
// reports (its steps), scored by CorrelativeScore, the best kept by the search's rule (the
// highest score, then the fewest steps from the centre, then the first in heading, x, y order).
template <class Lattice>
CorrelativeResult ExhaustiveSearch(const GridMap<Lattice>& grid,
                                   const std::vector<Eigen::Vector2d>& points, const Pose2& centre,
                                   const CorrelativeSearchOptions& options,
                                   const CorrelativeResult& searched) {
  const int n = static_cast<int>(std::floor(options.linear_window / searched.linear_step));
  const int m = static_cast<int>(std::floor(options.angular_window / searched.angular_step));
  CorrelativeResult best;
  best.score = -1.0;
  int best_move = 0;
  for (int ia = -m; ia <= m; ++ia) {
    for (int ix = -n; ix <= n; ++ix) {
      for (int iy = -n; iy <= n; ++iy) {
        const Pose2 pose(centre.x + ix * searched.linear_step, centre.y + iy * searched.linear_step,
                         centre.theta + ia * searched.angular_step);
        const double score = CorrelativeScore(grid, points, pose, options);
        const int move = std::abs(ia) + std::abs(ix) + std::abs(iy);
        ++best.candidates;
        if (score > best.score || (score == best.score && move < best_move)) {
          best.score = score;
          best.pose = pose;
          best_move = move;
        }
      }
    }
  }
  return best;
}

TYPED_TEST(CorrelativeSearchTest, AtOneHeadingTheSearchIsTheExhaustiveOneOverItsGrid) {
  // The search drops candidates that cannot reach the best score part-way through their points;
  // it must still return exactly what scoring every candidate in full returns. With no angular
  // window its candidates are known: the centre's heading, the translations centre + (i, j)·step,
  // each scored by ExhaustiveSearch.
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  RoomScans scans(4);
  CorrelativeSearchOptions options;
  options.linear_window = 0.6;
  options.angular_window = 0.0;
  const double step = options.step_cells * coarse.lattice().spacing();
  const int n = static_cast<int>(std::floor(options.linear_window / step));
  ASSERT_GE(n, 2);
  for (int trial = 0; trial < 12; ++trial) {
    const auto [truth, points, centre] = scans.Next(0.4, 0.05);
    const CorrelativeResult found = SearchCorrelative(coarse, points, centre, options);
    ASSERT_EQ(found.linear_step, step);
    const CorrelativeResult every = ExhaustiveSearch(coarse, points, centre, options, found);
    EXPECT_EQ(found.candidates, (2 * n + 1) * (2 * n + 1));
    EXPECT_EQ(found.score, every.score) << "trial " << trial;
    EXPECT_EQ(found.pose.x, every.pose.x) << "trial " << trial;
    EXPECT_EQ(found.pose.y, every.pose.y) << "trial " << trial;
    EXPECT_DOUBLE_EQ(found.pose.theta, NormalizeAngle(every.pose.theta)) << "trial " << trial;
  }
}

TYPED_TEST(CorrelativeSearchTest, OverEveryHeadingTheSearchIsTheExhaustiveOneOverItsGrid) {
  // The branch and bound rules out blocks of poses by bounds on a grid of pixels one step wide,
  // which do not line up with the cells: it must still return exactly the exhaustive search's
  // pose and score, ties included. Scans of 3 endpoints tie often (several poses put them on
  // the same cells); 40 m endpoints make the angular step fine and the headings many; a window
  // 500 m off the map ties everywhere.
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  RoomScans scans(6);
  CorrelativeSearchOptions options;
  options.linear_window = 0.5;
  options.angular_window = 0.3;
  int ties = 0, bounded = 0;
  for (int trial = 0; trial < 48; ++trial) {
    auto [truth, points, centre] = scans.Next(0.4, 0.25);
    if (trial % 3 == 1) points.resize(3);
    if (trial % 3 == 2) points.emplace_back(40.0, 0.0);
    if (trial % 8 == 7) centre.x += 500.0;  // off the map: every pose ties with the centre
    const CorrelativeResult found = SearchCorrelative(coarse, points, centre, options);
    const CorrelativeResult truth_search = ExhaustiveSearch(coarse, points, centre, options, found);
    ASSERT_TRUE(found.refused.empty()) << found.refused;
    if (found.branch_and_bound) ++bounded;
    EXPECT_EQ(found.candidates, truth_search.candidates) << "trial " << trial;
    EXPECT_EQ(found.score, truth_search.score) << "trial " << trial;
    EXPECT_EQ(found.pose.x, truth_search.pose.x) << "trial " << trial;
    EXPECT_EQ(found.pose.y, truth_search.pose.y) << "trial " << trial;
    EXPECT_DOUBLE_EQ(found.pose.theta, NormalizeAngle(truth_search.pose.theta))
        << "trial " << trial;
    // How many poses share the best score: the tie rule decided those trials.
    const Pose2 next(found.pose.x + found.linear_step, found.pose.y, found.pose.theta);
    if (CorrelativeScore(coarse, points, next, options) == found.score) ++ties;
  }
  EXPECT_GE(ties, 2);
  EXPECT_GE(bounded, 24);  // the branch and bound, not only the pose-by-pose path
}

TYPED_TEST(CorrelativeSearchTest, OnRandomMapsTheBranchAndBoundReturnsWhatEveryPoseScoredDoes) {
  // Random maps (free, occupied and unseen cells as mapping leaves them), scans, centres and
  // windows, with the branch and bound against the same search scoring every pose: the same
  // pose and score, to the last bit. Every other scan sees only a sector ahead (±0.6 rad, as a
  // lidar behind which the robot hides), where the bounds cover the box its endpoints sweep,
  // much less than the square round the farthest one.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> spacing(0.1, 0.3), unit(0.0, 1.0), centre(-1.5, 1.5);
  std::uniform_int_distribution<int> count(3, 60);
  int bounded = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const GridMap<TypeParam> grid = testing_util::RandomMap<TypeParam>(spacing(rng), &rng);
    std::vector<Eigen::Vector2d> points =
        testing_util::RandomPoints(count(rng), 0.5 + 5.0 * unit(rng), &rng);
    if (trial % 2 == 1) {
      for (Eigen::Vector2d& p : points) {
        const double a = 0.19 * std::atan2(p.y(), p.x());
        p = p.norm() * Eigen::Vector2d(std::cos(a), std::sin(a));
      }
    }
    CorrelativeSearchOptions options;
    options.linear_window = 0.6 * unit(rng);
    options.angular_window = 1.0 * unit(rng);
    options.step_cells = 0.3 + 0.5 * unit(rng);
    options.point_spacing_cells = unit(rng);
    const Pose2 at(centre(rng), centre(rng), M_PI * (2.0 * unit(rng) - 1.0));
    const CorrelativeResult found = SearchCorrelative(grid, points, at, options);
    options.branch_and_bound = false;
    const CorrelativeResult every = SearchCorrelative(grid, points, at, options);
    ASSERT_TRUE(found.refused.empty()) << found.refused;
    EXPECT_FALSE(every.branch_and_bound);
    if (found.branch_and_bound) ++bounded;
    EXPECT_EQ(found.candidates, every.candidates) << "trial " << trial;
    EXPECT_EQ(found.score, every.score) << "trial " << trial;
    EXPECT_EQ(found.pose.x, every.pose.x) << "trial " << trial;
    EXPECT_EQ(found.pose.y, every.pose.y) << "trial " << trial;
    EXPECT_EQ(found.pose.theta, every.pose.theta) << "trial " << trial;
  }
  EXPECT_GE(bounded, 30);
}

TYPED_TEST(CorrelativeSearchTest, APixelsBoundHoldsForEveryPointOfIt) {
  // The bounds' grid against dense sampling: no point of a pixel (its edges included) may fall
  // in a cell more probable than the pixel's bound. Pixels of 0.0731 m do not line up with
  // 0.2 m cells anywhere. Every pixel that meets the reach box is checked (the grid itself
  // stops where the written cells do); a search reads nothing beyond it.
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  const double pixel = 0.0731;
  const Eigen::AlignedBox2d reach(Eigen::Vector2d(-3.0, -2.0), Eigen::Vector2d(2.5, 3.0));
  const matching::PrecomputationGrid bounds = matching::PixelBounds(coarse, pixel, reach);
  constexpr int kSamples = 8;
  int tight = 0, pixels = 0;
  const Eigen::Array2i first = matching::PixelOf(reach.min(), pixel);
  const Eigen::Array2i last = matching::PixelOf(reach.max(), pixel);
  for (int x = first.x(); x <= last.x(); ++x) {
    for (int y = first.y(); y <= last.y(); ++y) {
      std::uint8_t most = 0;
      for (int i = 0; i <= kSamples; ++i) {
        for (int j = 0; j <= kSamples; ++j) {
          const Eigen::Vector2d p((x + static_cast<double>(i) / kSamples) * pixel,
                                  (y + static_cast<double>(j) / kSamples) * pixel);
          const float probability = coarse.Probability(coarse.lattice().CellOf(p));
          most = std::max(most, matching::QuantizeValueUp(probability));
        }
      }
      ASSERT_GE(bounds.CodeAt({x, y}), most) << "pixel " << x << ", " << y;
      ++pixels;
      if (bounds.CodeAt({x, y}) == most) ++tight;
    }
  }
  // Most pixels' bounds are what sampling finds; the rest count a cell that only nears them.
  EXPECT_GT(tight, pixels / 2);
  EXPECT_EQ(bounds.CodeAt(last + 1), matching::QuantizeValue(0.5f));
}

TYPED_TEST(CorrelativeSearchTest, BoundsThatWouldTakeMillionsOfPixelsAreNotBuilt) {
  // A step made very fine (4 mm on 0.2 m cells) would need a byte per 4 mm pixel over the whole
  // room (6 million) at every depth: the window is then scored pose by pose, within its budget.
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  RoomScans scans(7);
  const auto [truth, points, centre] = scans.Next(0.1, 0.01);
  CorrelativeSearchOptions options;
  options.step_cells = 0.02;
  options.linear_window = 0.8;  // 401 x 401 positions
  options.angular_window = 0.0;
  const CorrelativeResult found = SearchCorrelative(coarse, points, centre, options);
  ASSERT_TRUE(found.refused.empty()) << found.refused;
  EXPECT_FALSE(found.branch_and_bound);
  EXPECT_EQ(found.candidates, 401 * 401);
  options.step_cells = 0.5;  // the default: 0.1 m pixels, bounded
  EXPECT_TRUE(SearchCorrelative(coarse, points, centre, options).branch_and_bound);
}

TYPED_TEST(CorrelativeSearchTest, EndpointsKilometresAwayNeitherShrinkTheStepNorExceedTheBudget) {
  // Issue 12: a laser mounted 65 km from the base (a bad calibration line) made the angular step
  // 0.1 m / 65 km and the search run for minutes. The step stops at 1e-3 rad: 0.6 rad either side
  // is 1201 headings, times 9 x 9 positions (0.4 m either side in 0.1 m steps).
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  std::vector<Eigen::Vector2d> far;
  for (int i = 0; i < 20; ++i) far.emplace_back(65000.0 + 0.3 * i, 0.5 * i);
  CorrelativeSearchOptions options;
  const CorrelativeResult r = SearchCorrelative(coarse, far, Pose2(), options);
  EXPECT_TRUE(r.refused.empty()) << r.refused;
  EXPECT_EQ(r.candidates, 1201 * 9 * 9);
  options.max_candidates = 1201 * 9 * 9 - 1;
  const CorrelativeResult refused = SearchCorrelative(coarse, far, Pose2(0.1, 0.2, 0.3), options);
  EXPECT_EQ(refused.candidates, 0);
  EXPECT_DOUBLE_EQ(refused.pose.x, 0.1);
  EXPECT_NE(refused.refused.find("recovery_max_candidates"), std::string::npos) << refused.refused;
  // A window of any size is refused, not overflowed.
  options.linear_window = 1e300;
  EXPECT_FALSE(SearchCorrelative(coarse, far, Pose2(), options).refused.empty());
}

TYPED_TEST(CorrelativeSearchTest, AWindowOverItsBudgetIsSearchedOnACoarserGridThatFitsIt) {
  // The wide recovery's window can take more poses than the budget; allowed to, the search
  // coarsens its three steps alike until the window fits, and must still find the truth within
  // its (coarser) reach. Without that allowance, or when it would take more, it is refused and
  // names the window as asked.
  const MapPyramid<TypeParam> maps = MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  RoomScans scans(5);
  for (int trial = 0; trial < 6; ++trial) {
    const auto [truth, points, centre] = scans.Next(0.3, 0.5);
    CorrelativeSearchOptions options;
    const int asked = SearchCorrelative(coarse, points, centre, options).candidates;
    options.max_candidates = asked / 4;  // a cube-root factor of 1.6
    const CorrelativeResult refused = SearchCorrelative(coarse, points, centre, options);
    EXPECT_EQ(refused.candidates, 0);
    EXPECT_FALSE(refused.refused.empty());
    options.max_step_coarsening = 2.0;
    const CorrelativeResult found = SearchCorrelative(coarse, points, centre, options);
    ASSERT_TRUE(found.refused.empty()) << found.refused;
    EXPECT_LE(found.candidates, options.max_candidates);
    EXPECT_GT(found.step_coarsening, 1.5);
    EXPECT_LE(found.step_coarsening, 2.0);
    const double step = found.step_coarsening * options.step_cells * coarse.lattice().spacing();
    EXPECT_LT((found.pose.translation() - truth.translation()).norm(), 1.5 * step)
        << "trial " << trial;
    EXPECT_LT(std::abs(NormalizeAngle(found.pose.theta - truth.theta)),
              0.05 * found.step_coarsening)
        << "trial " << trial;
    options.max_candidates = asked / 10;  // would take 2.15 times coarser steps
    const CorrelativeResult too_far = SearchCorrelative(coarse, points, centre, options);
    EXPECT_EQ(too_far.candidates, 0);
    EXPECT_NE(too_far.refused.find(std::to_string(asked)), std::string::npos) << too_far.refused;
  }
  CorrelativeSearchOptions bad;
  bad.max_step_coarsening = 0.5;
  EXPECT_EQ(bad.Validate().size(), 1u);
}

TEST(CorrelativeSearchOptionsTest, ZeroWindowEvaluatesOnlyTheCentreAndBadValuesAreNamed) {
  const MapPyramid<HexLattice> maps = MapOfTestRoom<HexLattice>(0.05);
  const std::vector<Eigen::Vector2d> points = {{1.0, 0.0}, {0.0, 2.0}};
  const CorrelativeResult r = SearchCorrelative(maps.level(2), points, Pose2(0.1, 0.2, 0.3),
                                                CorrelativeSearchOptions{0.0, 0.0, 0.5, 1.0});
  EXPECT_EQ(r.candidates, 1);
  EXPECT_DOUBLE_EQ(r.pose.x, 0.1);
  const CorrelativeResult none =
      SearchCorrelative(maps.level(2), {}, Pose2(0.1, 0.2, 0.3), CorrelativeSearchOptions());
  EXPECT_EQ(none.candidates, 0);
  CorrelativeSearchOptions bad;
  bad.step_cells = 0.0;
  bad.linear_window = -1.0;
  EXPECT_EQ(bad.Validate().size(), 2u);
}

}  // namespace
}  // namespace hex_slam
