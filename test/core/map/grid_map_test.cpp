#include "hex_slam/map/grid_map.h"

#include <gtest/gtest.h>

#include "hex_slam/map/hex_grid.h"
#include "hex_slam/geometry/ray_traversal.h"
#include "hex_slam/map/square_grid.h"

namespace hex_slam {
namespace {

const OccupancyModel kModel = OccupancyModel::FromFactors(0.4, 0.9, 50.0);

Eigen::AlignedBox2d Box(double half) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(-half, -half), Eigen::Vector2d(half, half));
}

template <class T>
class GridMapTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(GridMapTest, Lattices);

TYPED_TEST(GridMapTest, OneBeamFreesItsPathAndHitsItsEndpoint) {
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, GridGrowthPolicy(), Box(5.0));
  const Eigen::Vector2d origin(0.02, -0.03), end(2.31, 1.17);
  grid.InsertScan(origin, {end});
  const auto end_cell = grid.lattice().CellOf(end);
  EXPECT_FLOAT_EQ(grid.LogOdds(end_cell), kModel.occupied_delta);
  std::vector<typename TypeParam::Cell> crossed;
  TraceRay(grid.lattice(), origin, end, &crossed);
  ASSERT_GT(crossed.size(), 10u);
  int known = 0;
  for (const auto& c : crossed) EXPECT_FLOAT_EQ(grid.LogOdds(c), kModel.free_delta);
  for (float v : grid.log_odds_grid().values()) known += v != 0.0f;
  EXPECT_EQ(known, static_cast<int>(crossed.size()) + 1);  // nothing else touched
  EXPECT_GT(grid.Probability(end_cell), 0.85f);
  EXPECT_LT(grid.Probability(crossed.front()), 0.45f);
}

TYPED_TEST(GridMapTest, EachCellChangesAtMostOncePerScanAndOccupiedWins) {
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, GridGrowthPolicy(), Box(5.0));
  const Eigen::Vector2d origin(0.0, 0.0);
  const Eigen::Vector2d wall(1.0, 0.0), beyond(2.0, 0.0);
  // Two beams to the same endpoint, and a third that passes through it: whatever the order, the
  // shared free cells get one free update and the wall cell exactly one occupied update.
  for (const auto& order : {std::vector<Eigen::Vector2d>{wall, wall, beyond},
                            std::vector<Eigen::Vector2d>{beyond, wall, wall}}) {
    grid.Clear();
    grid.InsertScan(origin, order);
    EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf(wall)), kModel.occupied_delta);
    EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf({0.5, 0.0})), kModel.free_delta);
    EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf(beyond)), kModel.occupied_delta);
  }
  // A second scan accumulates.
  grid.InsertScan(origin, {wall});
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf(wall)), 2 * kModel.occupied_delta);
}

TYPED_TEST(GridMapTest, GrowsToCoverFarScansAndKeepsWhatItHad) {
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, GridGrowthPolicy(), Box(1.0));
  grid.InsertScan({0.0, 0.0}, {{0.5, 0.5}});
  const auto first = grid.lattice().CellOf({0.5, 0.5});
  const std::size_t cells_before = grid.rect().size();
  grid.InsertScan({0.0, 0.0}, {{-7.0, 12.0}});
  EXPECT_GT(grid.rect().size(), cells_before);
  EXPECT_GE(grid.growth_count(), 1);
  EXPECT_FLOAT_EQ(grid.LogOdds(first), kModel.occupied_delta);
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf({-7.0, 12.0})), kModel.occupied_delta);
  EXPECT_TRUE(grid.StorageExtent().contains(Eigen::Vector2d(-7.0, 12.0)));
  EXPECT_EQ(grid.points_outside(), 0);
}

TYPED_TEST(GridMapTest, CappedGrowthCountsPointsItCannotStore) {
  GridGrowthPolicy growth;
  growth.max_cells = 2000;
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, growth, Box(1.0));
  grid.InsertScan({0.0, 0.0}, {{0.5, 0.0}, {50.0, 0.0}});
  EXPECT_EQ(grid.points_outside(), 1);
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf({0.5, 0.0})), kModel.occupied_delta);
  EXPECT_LE(static_cast<std::int64_t>(grid.rect().size()), growth.max_cells);
}

// Reserve sizes storage to the union of what it had and the box's cells, with no growth margin,
// and moves what was written; past the cell cap it refuses and changes nothing.
TYPED_TEST(GridMapTest, ReserveCoversExactlyTheBoxAndKeepsWhatItHad) {
  GridGrowthPolicy growth;
  growth.max_cells = 40000;
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, growth, Box(1.0));
  grid.InsertScan({0.0, 0.0}, {{0.5, 0.5}});
  const GridRect before = grid.rect();
  const Eigen::AlignedBox2d far(Eigen::Vector2d(3.0, -2.0), Eigen::Vector2d(6.0, 4.0));
  GridIndex lo, hi;
  grid.lattice().IndexBounds(far, &lo, &hi);
  const GridRect expected = before.Union(GridRect::FromCorners(lo, hi));
  ASSERT_TRUE(grid.Reserve(far));
  EXPECT_EQ(grid.rect().min.col, expected.min.col);
  EXPECT_EQ(grid.rect().min.row, expected.min.row);
  EXPECT_EQ(grid.rect().width, expected.width);
  EXPECT_EQ(grid.rect().height, expected.height);
  EXPECT_EQ(grid.growth_count(), 0);
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf({0.5, 0.5})), kModel.occupied_delta);
  // 60 m square at 0.1 m: far more than 40000 cells.
  const GridRect reserved = grid.rect();
  EXPECT_FALSE(grid.Reserve(Box(30.0)));
  EXPECT_EQ(grid.rect().size(), reserved.size());
  EXPECT_EQ(grid.rect().min.col, reserved.min.col);
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf({0.5, 0.5})), kModel.occupied_delta);
}

// Cut down to what its scans wrote, a grid reads the same everywhere, hit means included, and
// holds less: checked against an untouched copy, cell by cell over the whole former storage.
// (Resident storage, as submaps have, whose memory is all of it.)
TYPED_TEST(GridMapTest, ShrinkToWrittenKeepsEveryCellAndFreesTheRest) {
  GridGrowthPolicy growth;
  growth.prefault = true;
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, growth, Box(8.0));
  const Eigen::Vector2d origin(1.0, 0.5);
  for (int i = 0; i < 12; ++i) {
    const double a = 0.3 * i;
    grid.InsertScan(origin, {origin + Eigen::Vector2d(2.0 * std::cos(a), 1.5 * std::sin(a)),
                             origin + Eigen::Vector2d(1.1, -0.7 + 0.1 * i)});
  }
  const GridMap<TypeParam> before = grid;
  grid.ShrinkToWritten();
  EXPECT_LT(grid.rect().size(), before.rect().size() / 4);
  EXPECT_LT(grid.MemoryBytes(), before.MemoryBytes());
  const GridRect& all = before.rect();
  int known = 0, hit = 0;
  for (int row = all.min.row; row < all.min.row + all.height; ++row) {
    for (int col = all.min.col; col < all.min.col + all.width; ++col) {
      const GridIndex index{col, row};
      ASSERT_EQ(grid.LogOddsAt(index), before.LogOddsAt(index));
      ASSERT_EQ(grid.ProbabilityAt(index), before.ProbabilityAt(index));
      const CellHits& was = before.HitsAt(all.Offset(index));
      if (!grid.rect().Contains(index)) {
        ASSERT_EQ(was.count, 0.0f);
        continue;
      }
      const CellHits& is = grid.HitsAt(grid.rect().Offset(index));
      ASSERT_EQ(is.count, was.count);
      ASSERT_EQ(is.Mean(), was.Mean());
      known += before.IsKnownAt(index) ? 1 : 0;
      hit += was.count > 0.0f ? 1 : 0;
    }
  }
  EXPECT_GT(known, 50);
  EXPECT_GT(hit, 10);
  EXPECT_EQ(grid.hit_cells(), before.hit_cells());
}

// Shrinking lets go of what only insertion uses; a scan inserted after it must still update each
// cell once, as in a copy that was never shrunk (a beam crossing a cell another beam of the same
// scan hits, a cell two endpoints share).
TYPED_TEST(GridMapTest, AShrunkGridTakesLaterScansAsOneNeverShrunk) {
  GridGrowthPolicy growth;
  growth.prefault = true;
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, growth, Box(8.0));
  const Eigen::Vector2d origin(1.0, 0.5);
  const auto scan = [&](int i) {
    const double a = 0.3 * i;
    const Eigen::Vector2d far = origin + Eigen::Vector2d(2.0 * std::cos(a), 1.5 * std::sin(a));
    return std::vector<Eigen::Vector2d>{far, origin + 0.5 * (far - origin), far,
                                        origin + Eigen::Vector2d(1.1, -0.7 + 0.1 * i)};
  };
  for (int i = 0; i < 6; ++i) grid.InsertScan(origin, scan(i));
  GridMap<TypeParam> never_shrunk = grid;
  grid.ShrinkToWritten();
  EXPECT_LT(grid.MemoryBytes(), never_shrunk.MemoryBytes());
  // Past the shrunk storage too, so it grows again.
  const Eigen::Vector2d moved = origin + Eigen::Vector2d(0.5, 2.5);
  for (int i = 6; i < 12; ++i) {
    for (GridMap<TypeParam>* g : {&grid, &never_shrunk}) {
      g->InsertScan(origin, scan(i));
      g->InsertScan(moved, {moved + Eigen::Vector2d(0.3 * i - 2.0, 1.0)});
    }
  }
  const GridRect& all = never_shrunk.rect();
  int known = 0;
  for (int row = all.min.row; row < all.min.row + all.height; ++row) {
    for (int col = all.min.col; col < all.min.col + all.width; ++col) {
      const GridIndex index{col, row};
      ASSERT_EQ(grid.LogOddsAt(index), never_shrunk.LogOddsAt(index));
      ASSERT_EQ(grid.ProbabilityAt(index), never_shrunk.ProbabilityAt(index));
      known += never_shrunk.IsKnownAt(index) ? 1 : 0;
    }
  }
  EXPECT_GT(known, 50);
  EXPECT_EQ(grid.hit_cells(), never_shrunk.hit_cells());
}

TYPED_TEST(GridMapTest, NoGrowthWhenDisabled) {
  GridGrowthPolicy growth;
  growth.auto_grow = false;
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, growth, Box(1.0));
  const std::size_t cells = grid.rect().size();
  grid.InsertScan({0.0, 0.0}, {{5.0, 0.0}});
  EXPECT_EQ(grid.rect().size(), cells);
  EXPECT_EQ(grid.points_outside(), 1);
}

TYPED_TEST(GridMapTest, LogOddsAreClamped) {
  const OccupancyModel tight = OccupancyModel::FromFactors(0.4, 0.9, 3.0);
  GridMap<TypeParam> grid(TypeParam(0.1), tight, GridGrowthPolicy(), Box(2.0));
  for (int i = 0; i < 10; ++i) grid.InsertScan({0.0, 0.0}, {{1.0, 0.0}});
  EXPECT_FLOAT_EQ(grid.LogOdds(grid.lattice().CellOf({1.0, 0.0})), 3.0f);
}

TYPED_TEST(GridMapTest, ClearForgetsAndAssignRestores) {
  GridMap<TypeParam> grid(TypeParam(0.1), kModel, GridGrowthPolicy(), Box(2.0));
  grid.InsertScan({0.0, 0.0}, {{1.0, 0.3}, {-1.0, 0.7}});
  const GridRect rect = grid.rect();
  const std::vector<float> saved = grid.log_odds_grid().values();
  const Eigen::AlignedBox2d known = grid.KnownExtent();
  EXPECT_FALSE(known.isEmpty());
  grid.Clear();
  EXPECT_TRUE(grid.KnownExtent().isEmpty());
  for (std::size_t i = 0; i < grid.rect().size(); ++i) {
    ASSERT_EQ(grid.ProbabilityAt(grid.rect().IndexAt(i)), 0.5f);
  }
  grid.Assign(rect, saved);
  EXPECT_EQ(grid.log_odds_grid().values(), saved);
  EXPECT_GT(grid.Probability(grid.lattice().CellOf({1.0, 0.3})), 0.85f);
  EXPECT_THROW(grid.Assign(rect, std::vector<float>(3)), std::invalid_argument);
}

TYPED_TEST(GridMapTest, HitsRememberWhereInTheCellTheEndpointsFell) {
  GridMap<TypeParam> grid(TypeParam(0.2), kModel, GridGrowthPolicy(), Box(1.0));
  const auto cell = grid.lattice().CellOf({0.6, 0.2});
  const Eigen::Vector2d centre = grid.lattice().CentreOf(cell);
  const std::vector<Eigen::Vector2d> ends = {centre + Eigen::Vector2d(0.03, -0.02),
                                             centre + Eigen::Vector2d(0.05, 0.04),
                                             centre + Eigen::Vector2d(0.04, 0.01)};
  grid.InsertScan({0.0, 0.0}, {ends[0], ends[1]});  // two endpoints of one scan both count
  grid.InsertScan({0.0, 0.0}, {ends[2]});
  const std::size_t offset = grid.rect().Offset(TypeParam::ToIndex(cell));
  const CellHits& h = grid.HitsAt(offset);
  EXPECT_FLOAT_EQ(h.count, 3.0f);
  EXPECT_NEAR(h.Mean().x(), 0.04, 1e-6);
  EXPECT_NEAR(h.Mean().y(), 0.01, 1e-6);
  // The stored terms are the mean weighted by the cell's probability, the matcher's summands.
  EXPECT_FLOAT_EQ(h.weight, grid.ProbabilityAt(grid.rect().IndexAt(offset)));
  EXPECT_NEAR(h.x, h.weight * 0.04, 1e-6);
  // Cells the beams only crossed have no hits.
  EXPECT_EQ(grid.HitsAt(grid.rect().Offset(TypeParam::ToIndex(grid.lattice().CellOf({0.0, 0.0}))))
                .count,
            0.0f);
  // Growing keeps them; the running mean forgets beyond kHitMemory hits; Clear forgets all.
  grid.InsertScan({0.0, 0.0}, {{4.0, -3.0}});
  ASSERT_GT(grid.growth_count(), 0);
  const std::size_t moved = grid.rect().Offset(TypeParam::ToIndex(cell));
  EXPECT_NEAR(grid.HitsAt(moved).Mean().x(), 0.04, 1e-6);
  const Eigen::Vector2d elsewhere = centre + Eigen::Vector2d(-0.05, 0.0);
  for (int i = 0; i < 1000; ++i) grid.InsertScan({0.0, 0.0}, {elsewhere});
  EXPECT_FLOAT_EQ(grid.HitsAt(moved).count, GridMap<TypeParam>::kHitMemory);
  EXPECT_NEAR(grid.HitsAt(moved).Mean().x(), -0.05, 1e-4);
  grid.Clear();
  EXPECT_EQ(grid.hit_cells(), 0u);
  for (std::size_t i = 0; i < grid.rect().size(); ++i) ASSERT_EQ(grid.HitsAt(i).count, 0.0f);
}

TYPED_TEST(GridMapTest, AHitCellKeepsItsMeanWhenFreedToTheLogOddsLimit) {
  // The mean is stored weighted by the cell's probability; a cell freed by hundreds of beams
  // still reads it back, and its next hit moves it as a running mean should.
  GridMap<TypeParam> grid(TypeParam(0.2), kModel, GridGrowthPolicy(), Box(2.0));
  const auto cell = grid.lattice().CellOf({0.6, 0.2});
  const Eigen::Vector2d centre = grid.lattice().CentreOf(cell);
  grid.InsertScan({0.0, 0.0}, {centre + Eigen::Vector2d(0.03, -0.02)});
  const Eigen::Vector2d beyond = 2.5 * centre;  // beams from the origin through the cell
  for (int i = 0; i < 500; ++i) grid.InsertScan({0.0, 0.0}, {beyond});
  const std::size_t offset = grid.rect().Offset(TypeParam::ToIndex(cell));
  ASSERT_LT(grid.ProbabilityAt(grid.rect().IndexAt(offset)), 1e-15f);
  EXPECT_NEAR(grid.HitsAt(offset).Mean().x(), 0.03, 1e-6);
  EXPECT_NEAR(grid.HitsAt(offset).Mean().y(), -0.02, 1e-6);
  EXPECT_GT(grid.HitsAt(offset).weight, 0.0f);
  grid.InsertScan({0.0, 0.0}, {centre + Eigen::Vector2d(0.05, 0.0)});
  EXPECT_NEAR(grid.HitsAt(offset).Mean().x(), 0.04, 1e-6);
  EXPECT_NEAR(grid.HitsAt(offset).Mean().y(), -0.01, 1e-6);
}

}  // namespace
}  // namespace hex_slam
