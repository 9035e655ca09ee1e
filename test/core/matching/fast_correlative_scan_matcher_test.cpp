#include "hex_slam/matching/fast_correlative_scan_matcher.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "../test_maps.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/lattice_axes.h"
#include "hex_slam/geometry/square_lattice.h"
#include "random_maps.h"

namespace hex_slam {
namespace matching {
namespace {

using testing_util::CellValue;
using testing_util::RandomMap;
using testing_util::RandomPoints;

template <class T>
class FastCorrelativeScanMatcherTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(FastCorrelativeScanMatcherTest, Lattices);

struct Exhaustive {
  double score = -1.0;
  long candidates = 0;
};

// Every rotation and every offset of the window, each scored from the map's own accessors.
template <class Lattice>
Exhaustive ExhaustiveSearch(const GridMap<Lattice>& grid, const std::vector<DiscreteScan>& scans,
                            double unknown) {
  Exhaustive best;
  for (const DiscreteScan& scan : scans) {
    for (int x = scan.min_offset.x(); x <= scan.max_offset.x(); ++x) {
      for (int y = scan.min_offset.y(); y <= scan.max_offset.y(); ++y) {
        double sum = 0.0;
        for (const Eigen::Array2i& c : scan.cells) {
          sum += CellValue(grid, c + Eigen::Array2i(x, y), unknown);
        }
        best.score = std::max(best.score, sum / scan.cells.size());
        ++best.candidates;
      }
    }
  }
  return best;
}

// The score of a pose recomputed from world coordinates: the endpoints' cells at that pose.
template <class Lattice>
double ScoreAt(const GridMap<Lattice>& grid, const Pose2& pose,
               const std::vector<Eigen::Vector2d>& points, double unknown) {
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    sum += CellValue(grid, LatticeAxes<Lattice>::Of(grid.lattice().CellOf(pose * p)), unknown);
  }
  return sum / points.size();
}

// The goal of branch and bound: the optimum of the exhaustive search of the same discretised
// window, on random maps, scans, windows and depths.
TYPED_TEST(FastCorrelativeScanMatcherTest, FindsTheExhaustiveSearchsOptimumOnRandomMaps) {
  int compared = 0, pruned_most = 0;
  for (int seed = 0; seed < 40; ++seed) {
    std::mt19937_64 rng(1000 + seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> depth(1, 6), count(5, 60);
    const GridMap<TypeParam> grid = RandomMap<TypeParam>(0.05, &rng);
    FastCorrelativeScanMatcherOptions options;
    options.linear_search_window = 0.15 + 0.3 * (1.0 + u(rng));
    options.angular_search_window = 0.3 * (1.0 + u(rng));
    options.branch_and_bound_depth = depth(rng);
    const FastCorrelativeScanMatcher<TypeParam> matcher(grid, options);
    const std::vector<Eigen::Vector2d> points = RandomPoints(count(rng), 3.0, &rng);
    const Pose2 initial(1.5 * u(rng), 1.5 * u(rng), M_PI * u(rng));

    const std::vector<DiscreteScan> window = matcher.Window(initial, points, options.linear_search_window,
                                                             options.angular_search_window);
    const Exhaustive truth = ExhaustiveSearch(grid, window, options.unknown_probability);
    // A pose with every endpoint off the known cells scores exactly unknown_probability; above
    // it the optimum has an endpoint on the map, which the search cannot cut away.
    const double min_score = options.unknown_probability;
    const std::optional<CorrelativeMatch> found = matcher.Match(initial, points, min_score);
    if (truth.score <= min_score) {
      EXPECT_FALSE(found.has_value()) << "seed " << seed;
      continue;
    }
    ASSERT_TRUE(found.has_value()) << "seed " << seed;
    EXPECT_NEAR(found->score, truth.score, 1e-9) << "seed " << seed;
    EXPECT_NEAR(ScoreAt(grid, found->pose, points, options.unknown_probability), found->score,
                1e-9)
        << "seed " << seed;
    // Within the window: no farther than its corner, no more turned than its angular reach.
    EXPECT_LE(std::abs(NormalizeAngle(found->pose.theta - initial.theta)),
              options.angular_search_window +
                  AngularSearchStep(grid.lattice().spacing(), points) + 1e-12);
    EXPECT_FALSE(matcher.Match(initial, points, truth.score + 1e-6).has_value()) << "seed " << seed;
    ++compared;
    if (options.branch_and_bound_depth >= 4 && found->candidates * 4 < truth.candidates) {
      ++pruned_most;
    }
  }
  EXPECT_GE(compared, 30);
  // Not a speed test: that the bounds prune at all (the benchmark gives the figures).
  EXPECT_GT(pruned_most, 0);
}

TYPED_TEST(FastCorrelativeScanMatcherTest, FullSubmapSearchFindsTheExhaustiveOptimum) {
  for (int seed = 0; seed < 6; ++seed) {
    std::mt19937_64 rng(2000 + seed);
    const GridMap<TypeParam> grid = RandomMap<TypeParam>(0.1, &rng);
    FastCorrelativeScanMatcherOptions options;
    options.branch_and_bound_depth = 5;
    const FastCorrelativeScanMatcher<TypeParam> matcher(grid, options);
    const std::vector<Eigen::Vector2d> points = RandomPoints(25, 1.5, &rng);
    const std::optional<CorrelativeMatch> found =
        matcher.MatchFullSubmap(points, options.unknown_probability);
    ASSERT_TRUE(found.has_value()) << "seed " << seed;
    // The same rotations over every offset that could reach the map, and a margin beyond.
    const PrecomputationGrid& cells = matcher.grids().cells();
    const Eigen::Array2i middle = cells.origin() + cells.size() / 2;
    const Eigen::Vector2d t =
        LatticeAxes<TypeParam>::Basis(grid.lattice()) * middle.cast<double>().matrix();
    const double step = AngularSearchStep(grid.lattice().spacing(), points);
    const Eigen::Array2i reach = cells.size() + 40;
    const std::vector<DiscreteScan> all =
        DiscretizeScans(grid.lattice(), Pose2(t.x(), t.y(), 0.0), points, step,
                        static_cast<int>(std::ceil(M_PI / step)), -reach, reach);
    const Exhaustive truth = ExhaustiveSearch(grid, all, options.unknown_probability);
    EXPECT_NEAR(found->score, truth.score, 1e-9) << "seed " << seed;
    EXPECT_NEAR(ScoreAt(grid, found->pose, points, options.unknown_probability), found->score,
                1e-9);
  }
}

// The best pose of a window and the best one outside its peak (the runner-up's zone: more than
// the peak's angle, in whole rotation steps, or more than its cells along a lattice axis away),
// both by trying every pose.
struct BestAndRival {
  double best = -1.0;
  double rival = -1.0;
  bool unique = true;  // no other pose scores the best
};

template <class Lattice>
BestAndRival ExhaustiveBestAndRival(const GridMap<Lattice>& grid,
                                    const std::vector<DiscreteScan>& scans,
                                    const FastCorrelativeScanMatcherOptions& options) {
  auto score = [&](const DiscreteScan& scan, int x, int y) {
    double sum = 0.0;
    for (const Eigen::Array2i& c : scan.cells) {
      sum += CellValue(grid, c + Eigen::Array2i(x, y), options.unknown_probability);
    }
    return sum / scan.cells.size();
  };
  BestAndRival r;
  double best_theta = 0.0;
  Eigen::Array2i best_offset = Eigen::Array2i::Zero();
  for (const DiscreteScan& scan : scans) {
    for (int x = scan.min_offset.x(); x <= scan.max_offset.x(); ++x) {
      for (int y = scan.min_offset.y(); y <= scan.max_offset.y(); ++y) {
        const double s = score(scan, x, y);
        if (std::abs(s - r.best) < 1e-12) r.unique = false;
        if (s > r.best + 1e-12) {
          r = BestAndRival{s, -1.0, true};
          best_theta = scan.theta;
          best_offset = Eigen::Array2i(x, y);
        }
      }
    }
  }
  const double step = std::abs(scans[1].theta - scans[0].theta);
  const double angle = std::floor(options.peak_angle / step) * step + 1e-9;
  const int cells =
      OffsetsCovering(LatticeAxes<Lattice>::Basis(grid.lattice()), options.peak_radius).maxCoeff();
  for (const DiscreteScan& scan : scans) {
    for (int x = scan.min_offset.x(); x <= scan.max_offset.x(); ++x) {
      for (int y = scan.min_offset.y(); y <= scan.max_offset.y(); ++y) {
        const bool in_peak = std::abs(NormalizeAngle(scan.theta - best_theta)) <= angle &&
                             (Eigen::Array2i(x, y) - best_offset).abs().maxCoeff() <= cells;
        if (!in_peak) r.rival = std::max(r.rival, score(scan, x, y));
      }
    }
  }
  return r;
}

// A rival pose that scores ambiguity_ratio of the best makes the match ambiguous even when it
// scores below the search's min_score: a match that only just passes is no less ambiguous for
// its rival failing. Oracle: the exhaustive search of the window outside the best pose's peak.
TYPED_TEST(FastCorrelativeScanMatcherTest, ARivalBelowTheMinimumScoreStillMakesAMatchAmbiguous) {
  int checked = 0;
  for (int seed = 0; seed < 30; ++seed) {
    std::mt19937_64 rng(3000 + seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const GridMap<TypeParam> grid = RandomMap<TypeParam>(0.05, &rng);
    FastCorrelativeScanMatcherOptions options;
    options.linear_search_window = 0.6;
    options.angular_search_window = 0.6;
    options.branch_and_bound_depth = 4;
    const std::vector<Eigen::Vector2d> points = RandomPoints(30, 3.0, &rng);
    const Pose2 initial(1.5 * u(rng), 1.5 * u(rng), M_PI * u(rng));
    const std::vector<DiscreteScan> window =
        FastCorrelativeScanMatcher<TypeParam>(grid, options)
            .Window(initial, points, options.linear_search_window, options.angular_search_window);
    const BestAndRival truth = ExhaustiveBestAndRival(grid, window, options);
    // A rival off the map scores the unknown cells' value; one on it is what is meant.
    if (!truth.unique || truth.rival <= options.unknown_probability + 0.05) continue;
    const double min_score = 0.5 * (truth.rival + truth.best);
    options.ambiguity_ratio = 0.999 * truth.rival / truth.best;
    const std::optional<CorrelativeMatch> found =
        FastCorrelativeScanMatcher<TypeParam>(grid, options).Match(initial, points, min_score);
    ASSERT_TRUE(found.has_value()) << "seed " << seed;
    EXPECT_NEAR(found->score, truth.best, 1e-9) << "seed " << seed;
    EXPECT_NEAR(found->runner_up_score, truth.rival, 1e-9) << "seed " << seed;
    // A ratio just above the rival's: no runner-up.
    options.ambiguity_ratio = std::min(1.0, 1.001 * truth.rival / truth.best);
    const std::optional<CorrelativeMatch> clear =
        FastCorrelativeScanMatcher<TypeParam>(grid, options).Match(initial, points, min_score);
    ASSERT_TRUE(clear.has_value()) << "seed " << seed;
    EXPECT_EQ(clear->runner_up_score, 0.0) << "seed " << seed;
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// On a real map: a scan of the test room taken at a known pose is found from a guess metres and
// tens of degrees off, to within a cell and an angular step, and refound from nowhere by the
// full-submap search.
TYPED_TEST(FastCorrelativeScanMatcherTest, FindsATrueScanPoseFarFromTheGuess) {
  const MapPyramid<TypeParam> maps = testing_util::MapOfTestRoom<TypeParam>(0.05);
  const GridMap<TypeParam>& grid = maps.level(0);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 360;
  FastCorrelativeScanMatcherOptions options;
  options.linear_search_window = 1.5;
  const FastCorrelativeScanMatcher<TypeParam> matcher(grid, options);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const Pose2 truth = testing_util::GenericPlacement() * Pose2(1.0 * u(rng), 1.0 * u(rng), M_PI * u(rng));
    const std::vector<Eigen::Vector2d> points =
        testing_util::ScanPoints(world, truth, lidar, &rng);
    const Pose2 guess(truth.x + 1.2 * u(rng), truth.y + 1.2 * u(rng), truth.theta + 0.45 * u(rng));
    const double step = AngularSearchStep(grid.lattice().spacing(), points);
    for (const std::optional<CorrelativeMatch>& found :
         {matcher.Match(guess, points, 0.5), matcher.MatchFullSubmap(points, 0.5)}) {
      ASSERT_TRUE(found.has_value()) << "trial " << trial;
      EXPECT_LT((found->pose.translation() - truth.translation()).norm(),
                1.5 * grid.lattice().spacing())
          << "trial " << trial;
      EXPECT_LT(std::abs(NormalizeAngle(found->pose.theta - truth.theta)), 1.5 * step)
          << "trial " << trial;
    }
  }
}

// A search over every heading has rotations on both sides of ±π that are the same pose. The
// runner-up (another place the scan fits about as well) must lie outside the best pose's peak
// as angles compare, not as rotation indices do: a robot heading ~π was reported ambiguous
// against itself, and the ROSbot's localizer refused the right place.
TYPED_TEST(FastCorrelativeScanMatcherTest, ARobotHeadingNearPiIsNotAmbiguousWithItself) {
  const MapPyramid<TypeParam> maps = testing_util::MapOfTestRoom<TypeParam>(0.05);
  const GridMap<TypeParam>& grid = maps.level(maps.size() - 1);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 360;
  const FastCorrelativeScanMatcherOptions options;
  const FastCorrelativeScanMatcher<TypeParam> matcher(grid, options);
  std::mt19937_64 rng(4);
  for (const double heading : {0.3, M_PI - 0.01, -M_PI + 0.01, M_PI - 0.1, -M_PI + 0.1}) {
    const Pose2 place = testing_util::GenericPlacement() * Pose2(0.2, -0.1, 0.0);
    const Pose2 truth(place.x, place.y, heading);  // the heading in the map's frame
    const std::vector<Eigen::Vector2d> points =
        testing_util::ScanPoints(world, truth, lidar, &rng);
    const std::optional<CorrelativeMatch> found = matcher.MatchFullSubmap(points, 0.5);
    ASSERT_TRUE(found.has_value()) << "heading " << heading;
    EXPECT_LT(std::abs(NormalizeAngle(found->pose.theta - truth.theta)), options.peak_angle)
        << "heading " << heading;
    if (found->runner_up_score > 0.0) {
      // Whatever it is, it is not the best pose again.
      const bool other_heading =
          std::abs(NormalizeAngle(found->runner_up_pose.theta - found->pose.theta)) >
          options.peak_angle;
      const bool other_place =
          (found->runner_up_pose.translation() - found->pose.translation()).norm() >
          options.peak_radius;
      EXPECT_TRUE(other_heading || other_place)
          << "heading " << heading << ": runner-up at heading " << found->runner_up_pose.theta
          << ", best at " << found->pose.theta;
    }
    EXPECT_EQ(found->runner_up_score, 0.0) << "heading " << heading;
  }
}

TEST(FastCorrelativeScanMatcherOptionsTest, BadValuesAreNamed) {
  FastCorrelativeScanMatcherOptions o;
  EXPECT_TRUE(o.Validate().empty());
  o.linear_search_window = -1.0;
  o.angular_search_window = 4.0;
  o.branch_and_bound_depth = 0;
  o.unknown_probability = 1.5;
  const std::vector<std::string> errors = o.Validate();
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_NE(errors[0].find("loop_closure_linear_search_window"), std::string::npos);
  EXPECT_NE(errors[2].find("loop_closure_branch_and_bound_depth"), std::string::npos);
}

TEST(FastCorrelativeScanMatcherTest, AnEmptyScanOrMapMatchesNothing) {
  const GridMap<HexLattice> empty(HexLattice(0.05), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                                  GridGrowthPolicy(),
                                  Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
  const FastCorrelativeScanMatcher<HexLattice> matcher(empty, FastCorrelativeScanMatcherOptions());
  EXPECT_FALSE(matcher.Match(Pose2(), {{1.0, 0.0}}, 0.0).has_value());
  EXPECT_FALSE(matcher.MatchFullSubmap({{1.0, 0.0}}, 0.0).has_value());
  std::mt19937_64 rng(1);
  const GridMap<HexLattice> grid = RandomMap<HexLattice>(0.05, &rng);
  const FastCorrelativeScanMatcher<HexLattice> full(grid, FastCorrelativeScanMatcherOptions());
  EXPECT_FALSE(full.Match(Pose2(), {}, 0.0).has_value());
}

}  // namespace
}  // namespace matching
}  // namespace hex_slam
