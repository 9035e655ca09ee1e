#include "hex_slam/io/map_image.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hex_slam/map/hex_grid.h"

namespace hex_slam {
namespace io {
namespace {

TEST(MapImageTest, PixelsShowTheirCellsOccupancyAndOutlinesFollowHexBoundaries) {
  GridMap<HexLattice> grid(HexLattice(0.2), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                           GridGrowthPolicy(),
                           Eigen::AlignedBox2d(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3)));
  std::vector<Eigen::Vector2d> wall;
  for (double y = -1.0; y <= 1.0; y += 0.05) wall.emplace_back(2.0, y);
  grid.InsertScan({0.0, 0.0}, wall);
  MapImageOptions options;
  options.pixels_per_metre = 100.0;
  ImageFrame frame;
  const Image image = RenderMap(grid, options, &frame);
  ASSERT_EQ(image.channels, 3);
  ASSERT_GT(image.width, 200);
  // A pixel well inside the occupied cell under the wall is dark; one in a free cell is light.
  const Eigen::Vector2d wall_centre = grid.lattice().CentreOf(grid.lattice().CellOf({2.0, 0.0}));
  const Eigen::Vector2d dark = frame.ToPixel(wall_centre);
  EXPECT_LT(image.at(static_cast<int>(dark.x()), static_cast<int>(dark.y()))[0], 60);
  const Eigen::Vector2d free_centre = grid.lattice().CentreOf(grid.lattice().CellOf({1.0, 0.0}));
  const Eigen::Vector2d light = frame.ToPixel(free_centre);
  EXPECT_GT(image.at(static_cast<int>(light.x()), static_cast<int>(light.y()))[0], 140);
  // Outline pixels: along a row through a band of free cells the colour changes exactly where
  // the cell under the pixel changes.
  const int y = static_cast<int>(light.y());
  int boundaries = 0;
  for (int x = 1; x < image.width; ++x) {
    const bool changed = grid.lattice().CellOf(frame.ToWorld(x, y)) !=
                         grid.lattice().CellOf(frame.ToWorld(x - 1, y));
    const auto cell = grid.lattice().CellOf(frame.ToWorld(x, y));
    if (changed && grid.LogOdds(cell) != 0.0f) {
      ++boundaries;
      const long undarkened = std::lround(255.0 * (1.0 - grid.Probability(cell)));
      EXPECT_LT(image.at(x, y)[0], undarkened) << "x " << x;
    }
  }
  EXPECT_GT(boundaries, 5);
}

TEST(MapImageTest, OverlaysLandWhereTheWorldPointIs) {
  ImageFrame frame = ImageFrame::Covering(
      Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 1)), 50.0);
  EXPECT_EQ(frame.width, 100);
  EXPECT_EQ(frame.height, 50);
  Image image(frame.width, frame.height, 3, 255);
  DrawDisc(frame, {1.0, 0.5}, 2, {255, 0, 0}, &image);
  EXPECT_EQ(image.at(50, 25)[1], 0);
  EXPECT_EQ(image.at(10, 10)[1], 255);
  DrawPolyline(frame, {{0.1, 0.1}, {1.9, 0.1}}, {0, 0, 255}, 1, &image);
  EXPECT_EQ(image.at(50, 45)[0], 0);
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
