#include "hex_slam/io/occupancy_raster.h"

#include <gtest/gtest.h>

#include "hex_slam/map/hex_grid.h"
#include "hex_slam/map/square_grid.h"

namespace hex_slam {
namespace io {
namespace {

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
  // Every pixel agrees with the cell under its centre.
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const float l = grid.LogOdds(grid.lattice().CellOf(raster.PixelCentre(col, row)));
      const int expected = l > 0 ? 100 : l < 0 ? 0 : -1;
      ASSERT_EQ(raster.at(col, row), expected);
    }
  }
  // The origin snaps to the world-anchored pixel grid.
  EXPECT_NEAR(std::remainder(raster.origin.x(), 0.05), 0.0, 1e-9);
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
