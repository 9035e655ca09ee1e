#include "hex_slam/io/occupancy_raster.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/map/hex_grid.h"
#include "hex_slam/map/square_grid.h"

namespace hex_slam {
namespace io {
namespace {

// For each occupied cell, found cell by cell over the grid's storage, the pixels whose closed
// square holds its centre: one, or two to four where the centre lies on pixel edges (on the hex
// lattice every other row of centres does), where either side may take it.
using Pixel = std::pair<int, int>;
template <class Lattice>
std::vector<std::set<Pixel>> PixelsHoldingOccupiedCentres(const GridMap<Lattice>& grid,
                                                          const OccupancyRaster& raster) {
  std::vector<std::set<Pixel>> cells;
  const GridRect& rect = grid.log_odds_grid().rect();
  for (int row = rect.min.row; row < rect.min.row + rect.height; ++row) {
    for (int col = rect.min.col; col < rect.min.col + rect.width; ++col) {
      if (!(grid.log_odds_grid().LogOddsAt({col, row}) > 0.0f)) continue;
      const Eigen::Vector2d q =
          (grid.lattice().CentreOf(GridIndex{col, row}) - raster.origin) / raster.resolution;
      std::set<Pixel> pixels;
      for (double dx : {-1e-6, 1e-6}) {
        for (double dy : {-1e-6, 1e-6}) {
          const int c = static_cast<int>(std::floor(q.x() + dx));
          const int r = static_cast<int>(std::floor(q.y() + dy));
          if (c >= 0 && r >= 0 && c < raster.width && r < raster.height) pixels.insert({c, r});
        }
      }
      if (!pixels.empty()) cells.push_back(pixels);
    }
  }
  return cells;
}

bool ShowsOnePixel(const std::set<Pixel>& pixels, const OccupancyRaster& raster) {
  return std::any_of(pixels.begin(), pixels.end(), [&](const Pixel& p) {
    return raster.at(p.first, p.second) == OccupancyRaster::kOccupied;
  });
}

template <class T>
class RasterTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(RasterTest, Lattices);

TYPED_TEST(RasterTest, WallsOccupiedRaysFreeRestUnknown) {
  GridMap<TypeParam> grid(TypeParam(0.1), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                          GridGrowthPolicy(),
                          Eigen::AlignedBox2d(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3)));
  std::vector<Eigen::Vector2d> wall;
  for (double y = -1.0; y <= 1.0; y += 0.02) wall.emplace_back(2.0, y);
  grid.InsertScan({0.0, 0.0}, wall);
  const OccupancyRaster raster = Rasterize(grid.log_odds_grid(), 0.05);
  ASSERT_GT(raster.width, 0);
  auto value_at = [&raster](const Eigen::Vector2d& p) {
    const Eigen::Vector2d q = (p - raster.origin) / raster.resolution;
    return raster.at(static_cast<int>(q.x()), static_cast<int>(q.y()));
  };
  EXPECT_EQ(value_at({2.0, 0.3}), OccupancyRaster::kOccupied);
  EXPECT_EQ(value_at({1.0, 0.1}), OccupancyRaster::kFree);
  EXPECT_EQ(value_at({0.3, -0.2}), OccupancyRaster::kFree);
  // Behind the wall, and off to the side, nothing was seen.
  EXPECT_EQ(value_at({2.3, 0.0}), OccupancyRaster::kUnknown);
  EXPECT_EQ(value_at({0.5, 0.9}), OccupancyRaster::kUnknown);
  // Every pixel agrees with the cell under its centre, or holds an occupied cell's centre.
  std::set<Pixel> holding;
  for (const std::set<Pixel>& pixels : PixelsHoldingOccupiedCentres(grid, raster)) {
    holding.insert(pixels.begin(), pixels.end());
  }
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const float l = grid.LogOdds(grid.lattice().CellOf(raster.PixelCentre(col, row)));
      const int expected = l > 0 ? 100 : l < 0 ? 0 : -1;
      const int value = raster.at(col, row);
      ASSERT_TRUE(value == expected || (value == 100 && holding.count({col, row})))
          << col << " " << row;
    }
  }
  // Pixel centres on the world-anchored multiples of the resolution.
  EXPECT_NEAR(std::remainder(raster.PixelCentre(0, 0).x(), 0.05), 0.0, 1e-9);
  EXPECT_NEAR(std::remainder(raster.PixelCentre(0, 0).y(), 0.05), 0.0, 1e-9);
}

// A wall one cell thick, turned 0.3 rad against the rows (as the rostests' room is), seen from
// several places so that its cells are occupied all along.
template <class Lattice>
GridMap<Lattice> SlantedWall(double spacing) {
  GridMap<Lattice> grid(Lattice(spacing), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                        GridGrowthPolicy(),
                        Eigen::AlignedBox2d(Eigen::Vector2d(-4, -4), Eigen::Vector2d(4, 4)));
  const Eigen::Vector2d a(2.0, -1.5), b(2.0 + 3.0 * std::sin(0.3), -1.5 + 3.0 * std::cos(0.3));
  std::vector<Eigen::Vector2d> wall;
  for (double t = 0.0; t <= 1.0; t += 0.002) wall.push_back(a + t * (b - a));
  for (double y : {-1.0, 0.0, 1.0}) grid.InsertScan({0.0, y}, wall);
  return grid;
}

// At its own spacing a square lattice's raster is the grid itself: one pixel a cell, each with
// the cell's value (before pixel centres were moved onto cell centres they sat on cell
// boundaries, and rounding dropped rows of cells).
TEST(RasterTest, SquareLatticeAtItsSpacingIsRasterisedCellForCell) {
  for (double spacing : {0.05, 0.046530243, 0.1}) {
    const GridMap<SquareLattice> grid = SlantedWall<SquareLattice>(spacing);
    const OccupancyRaster raster = Rasterize(grid.log_odds_grid(), spacing);
    int occupied_cells = 0, occupied_pixels = 0;
    grid.log_odds_grid().ForEachKnown([&](std::size_t, const GridIndex& index, float l) {
      occupied_cells += l > 0;
      const Eigen::Vector2d q = (grid.lattice().CentreOf(index) - raster.origin) / spacing;
      // The cell's centre is its pixel's centre.
      EXPECT_NEAR(q.x() - std::floor(q.x()), 0.5, 1e-6);
      EXPECT_NEAR(q.y() - std::floor(q.y()), 0.5, 1e-6);
      const int expected = l > 0 ? 100 : 0;
      EXPECT_EQ(raster.at(static_cast<int>(q.x()), static_cast<int>(q.y())), expected);
    });
    for (std::int8_t v : raster.data) occupied_pixels += v == OccupancyRaster::kOccupied;
    ASSERT_GT(occupied_cells, 2.5 / spacing);  // the wall is 3 m long
    EXPECT_EQ(occupied_pixels, occupied_cells) << "spacing " << spacing;
  }
}

// Every occupied cell shows, and a wall of cells stays one unbroken line of pixels (8-connected
// from one end to the other) on both lattices, at the pixel /map uses and at a coarser one.
TYPED_TEST(RasterTest, ASlantedWallShowsEveryCellWithoutAGap) {
  for (double resolution : {0.05, 0.08}) {
    const GridMap<TypeParam> grid = SlantedWall<TypeParam>(0.05);
    const OccupancyRaster raster = Rasterize(grid.log_odds_grid(), resolution);
    const std::vector<std::set<Pixel>> cells = PixelsHoldingOccupiedCentres(grid, raster);
    ASSERT_GT(cells.size(), 2.5 / 0.05);
    std::vector<Pixel> shown;
    for (const std::set<Pixel>& pixels : cells) {
      EXPECT_TRUE(ShowsOnePixel(pixels, raster)) << pixels.begin()->first << " "
                                                            << pixels.begin()->second;
      for (const Pixel& p : pixels) {
        if (raster.at(p.first, p.second) == OccupancyRaster::kOccupied) shown.push_back(p);
      }
    }
    ASSERT_FALSE(shown.empty());
    auto lower = [](const Pixel& a, const Pixel& b) { return a.second < b.second; };
    // Flood the occupied pixels from the lowest wall pixel; the highest must be reached.
    std::set<Pixel> reached{*std::min_element(shown.begin(), shown.end(), lower)};
    std::vector<Pixel> frontier(reached.begin(), reached.end());
    while (!frontier.empty()) {
      const auto [col, row] = frontier.back();
      frontier.pop_back();
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int c = col + dc, r = row + dr;
          if (c < 0 || r < 0 || c >= raster.width || r >= raster.height) continue;
          if (raster.at(c, r) != OccupancyRaster::kOccupied || !reached.insert({c, r}).second) {
            continue;
          }
          frontier.push_back({c, r});
        }
      }
    }
    EXPECT_TRUE(reached.count(*std::max_element(shown.begin(), shown.end(), lower)))
        << "resolution " << resolution;
  }
}

TEST(RasterTest, EmptyMapGivesEmptyRaster) {
  GridMap<HexLattice> grid(HexLattice(0.1), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                           GridGrowthPolicy(),
                           Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
  EXPECT_EQ(Rasterize(grid.log_odds_grid(), 0.05).width, 0);
  EXPECT_THROW(Rasterize(grid.log_odds_grid(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
