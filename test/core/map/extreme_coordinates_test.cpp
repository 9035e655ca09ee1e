// NaN, infinite and enormous coordinates through every path from a point to a cell: the lattices,
// the map update, ray traversal, the matchers and the recovery search. Before issue 12 these cast
// doubles beyond int's range to int (undefined behaviour; UBSan: float-cast-overflow at
// hex_lattice.cpp:20 and grid_index.h:22), overflowed the indices and wrote outside the map. Run
// under scripts/test_sanitizers, any such cast or write aborts the test.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/matching/correlative_search.h"
#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/hex_scan_matcher.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/geometry/ray_traversal.h"
#include "hex_slam/geometry/square_lattice.h"
#include "hex_slam/matching/square_scan_matcher.h"
#include "../test_maps.h"

namespace hex_slam {
namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kValues[] = {kNan, kInf, -kInf, 1e300, -1e300, 1e15, -1e15, 1e9, -1e9, 0.0};

std::vector<Eigen::Vector2d> HostilePoints() {
  std::vector<Eigen::Vector2d> points;
  for (double x : kValues) {
    for (double y : kValues) points.emplace_back(x, y);
  }
  return points;
}

bool IsFar(const Eigen::Vector2d& p) { return !(p.cwiseAbs().maxCoeff() < 1e6); }

// What every cell of `grid` holds, read through its public accessors.
template <class Lattice>
std::vector<float> Cells(const GridMap<Lattice>& grid) {
  std::vector<float> values;
  const GridRect& r = grid.rect();
  for (int row = r.min.row; row < r.min.row + r.height; ++row) {
    for (int col = r.min.col; col < r.min.col + r.width; ++col) {
      values.push_back(grid.LogOddsAt({col, row}));
    }
  }
  return values;
}

template <class T>
class ExtremeCoordinatesTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(ExtremeCoordinatesTest, Lattices);

TYPED_TEST(ExtremeCoordinatesTest, FarPointsNameCellsOutsideAMapOfTheLargestSize) {
  const TypeParam lattice(0.05);
  // A map 1 km across around the origin (far more cells than map_max_cells allows) holds no
  // point beyond 1e6 m, NaN or infinite: their cells are clamped, not wrapped around into it.
  GridIndex lo, hi;
  lattice.IndexBounds(Eigen::AlignedBox2d(Eigen::Vector2d(-500, -500), Eigen::Vector2d(500, 500)),
                      &lo, &hi);
  const GridRect big = GridRect::FromCorners(lo, hi);
  for (const Eigen::Vector2d& p : HostilePoints()) {
    const GridIndex index = TypeParam::ToIndex(lattice.CellOf(p));
    EXPECT_LE(std::abs(static_cast<long long>(index.col)), 2LL * kMaxCellIndex);
    EXPECT_LE(std::abs(static_cast<long long>(index.row)), 2LL * kMaxCellIndex);
    if (IsFar(p)) {
      EXPECT_FALSE(big.Contains(index)) << p.transpose();
    }
    Eigen::AlignedBox2d box(p);
    box.extend(Eigen::Vector2d(1.0, 1.0));
    lattice.IndexBounds(box, &lo, &hi);
    EXPECT_LE(std::abs(static_cast<long long>(lo.col)), kMaxCellIndex + 1LL);
    EXPECT_LE(std::abs(static_cast<long long>(hi.row)), kMaxCellIndex + 1LL);
  }
}

TYPED_TEST(ExtremeCoordinatesTest, InsertScanIgnoresWhatNoMapCanHoldAndChangesNothingElse) {
  const OccupancyModel model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  GridGrowthPolicy growth;
  growth.max_cells = 1 << 16;
  GridMap<TypeParam> grid(TypeParam(0.1), model, growth,
                          Eigen::AlignedBox2d(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2)));
  grid.InsertScan(Eigen::Vector2d(0.0, 0.0), {Eigen::Vector2d(1.0, 0.5)});
  const std::vector<float> before = Cells(grid);
  const GridRect rect = grid.rect();
  const std::vector<Eigen::Vector2d> points = HostilePoints();
  std::vector<Eigen::Vector2d> far;
  for (const Eigen::Vector2d& p : points) {
    if (IsFar(p)) far.push_back(p);
  }
  // Far endpoints from a sane origin, and every hostile origin with them.
  grid.InsertScan(Eigen::Vector2d(0.0, 0.0), far);
  for (const Eigen::Vector2d& origin : far) grid.InsertScan(origin, far);
  EXPECT_EQ(grid.rect().width, rect.width) << "the map grew towards a point no map can hold";
  EXPECT_EQ(grid.rect().height, rect.height);
  EXPECT_EQ(Cells(grid), before);
  EXPECT_GT(grid.points_outside(), 0);
}

TYPED_TEST(ExtremeCoordinatesTest, RayTraversalOfHostileSegmentsEndsWithinItsCap) {
  // A segment with an end beyond the index range (2^28 cells, 13,000 km of 5 cm cells) is not
  // walked; a walk within it is capped at 2^24 cells, more than any map holds in a row.
  const TypeParam lattice(0.05);
  std::vector<typename TypeParam::Cell> cells;
  for (const Eigen::Vector2d& a : HostilePoints()) {
    for (const Eigen::Vector2d& b : {Eigen::Vector2d(kNan, 1.0), Eigen::Vector2d(1e300, -1e300),
                                     Eigen::Vector2d(-kInf, 0.0), Eigen::Vector2d(0.3, 0.2)}) {
      TraceRay(lattice, a, b, &cells);
      if (IsFar(a) || IsFar(b)) {
        EXPECT_LE(cells.size(), 1u) << a.transpose() << " -> " << b.transpose();
      }
    }
  }
  // 1e6 m is inside the range: 4e7 cells crossed, walked up to the cap.
  TraceRay(lattice, Eigen::Vector2d(1e6, 0.0), Eigen::Vector2d(0.3, 0.2), &cells);
  EXPECT_EQ(cells.size(), std::size_t{1} << 24);
  // A sane one is walked whole: about 2L/d cells (hexagons) or |dx| + |dy| + 1 (squares).
  TraceRay(lattice, Eigen::Vector2d(0.01, 0.02), Eigen::Vector2d(10.0, 3.0), &cells);
  EXPECT_GT(cells.size(), 200u);
  EXPECT_LT(cells.size(), 500u);
}

TYPED_TEST(ExtremeCoordinatesTest, RecoverySearchAroundAHostileCentreScoresNothingKnown) {
  const MapPyramid<TypeParam> maps = testing_util::MapOfTestRoom<TypeParam>(0.05);
  const auto& coarse = maps.level(maps.size() - 1);
  const std::vector<Eigen::Vector2d> scan = {{1.0, 0.0}, {0.0, 1.5}, {-2.0, 0.3}};
  for (double v : {kInf, 1e300, 1e15, std::nan("")}) {
    const CorrelativeResult r =
        SearchCorrelative(coarse, scan, Pose2(v, -v, 0.0), CorrelativeSearchOptions());
    EXPECT_TRUE(r.refused.empty()) << r.refused;
    EXPECT_DOUBLE_EQ(r.score, GridMap<TypeParam>::kUnknownProbability);
  }
}

template <class Lattice>
MatchResult MatchOn(const MapPyramid<Lattice>& maps, const std::vector<Eigen::Vector2d>& points,
                    const Pose2& guess);
template <>
MatchResult MatchOn(const MapPyramid<HexLattice>& maps,
                    const std::vector<Eigen::Vector2d>& points, const Pose2& guess) {
  return HexScanMatcher(ScanMatcherOptions()).Match(maps, points, guess);
}
template <>
MatchResult MatchOn(const MapPyramid<SquareLattice>& maps,
                    const std::vector<Eigen::Vector2d>& points, const Pose2& guess) {
  return SquareScanMatcher(ScanMatcherOptions()).Match(maps, points, guess);
}

TYPED_TEST(ExtremeCoordinatesTest, MatchingFromAHostileGuessReadsNoCellItShouldNot) {
  // The matcher's interpolation floors every endpoint per iteration (FloorToInt): from a far or
  // non-finite guess every endpoint lies outside the map and reads "unknown".
  const MapPyramid<TypeParam> maps = testing_util::MapOfTestRoom<TypeParam>(0.05);
  std::vector<Eigen::Vector2d> scan;
  for (int i = 0; i < 60; ++i) scan.emplace_back(2.0 * std::cos(0.1 * i), 1.5 * std::sin(0.1 * i));
  for (double v : {1e300, -1e15, 1e9}) {
    const Pose2 guess(v, -v, 1.0);
    const MatchResult r = MatchOn(maps, scan, guess);
    // Nothing known there, so nothing may move the pose (beyond rounding at that magnitude).
    EXPECT_NEAR(r.pose.x, guess.x, 1e-12 * std::abs(v)) << v;
    EXPECT_NEAR(r.pose.y, guess.y, 1e-12 * std::abs(v)) << v;
  }
  // Non-finite guesses and endpoints: what comes out is not checked (the SLAM core's sanitizer
  // and odometry checks keep them out), only that no cell outside the map is read (sanitizers).
  for (double v : {kNan, kInf}) MatchOn(maps, scan, Pose2(v, 0.0, 0.0));
  MatchOn(maps, HostilePoints(), Pose2());
}

}  // namespace
}  // namespace hex_slam
