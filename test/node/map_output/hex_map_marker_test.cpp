#include "map_output/hex_map_marker.h"

#include <gtest/gtest.h>

#include "wall_map.h"

namespace hex_slam {
namespace node {
namespace {

using testing_util::HectorModel;
using testing_util::Square;

template <class Lattice>
GridMap<Lattice> WallGrid() {
  GridMap<Lattice> grid(Lattice(0.1), HectorModel(), GridGrowthPolicy(), Square(2.0));
  testing_util::InsertWall(1.0, 0.5, &grid);
  return grid;
}

int KnownCells(const std::vector<float>& log_odds) {
  int known = 0;
  for (float v : log_odds) known += v != 0.0f;
  return known;
}

TEST(HexMapMarkerTest, OneHexagonPerKnownCellColouredByOccupancy) {
  const GridMap<HexLattice> grid = WallGrid<HexLattice>();
  const int known = KnownCells(grid.log_odds_grid().values());
  ASSERT_GT(known, 50);
  MarkerStats stats;
  const visualization_msgs::Marker m =
      MakeHexMapMarker(grid.log_odds_grid(), MarkerStyle(), "map", ros::Time(1), &stats);
  EXPECT_EQ(m.type, visualization_msgs::Marker::TRIANGLE_LIST);
  EXPECT_EQ(m.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(m.header.frame_id, "map");
  EXPECT_EQ(stats.known_cells, known);
  EXPECT_EQ(stats.drawn_cells, known);
  constexpr int kVerticesPerHexagon = 4 * 3;  // four triangles
  ASSERT_EQ(m.points.size(), static_cast<std::size_t>(known * kVerticesPerHexagon));
  ASSERT_EQ(m.colors.size(), m.points.size());
  const double circumradius = 0.1 / std::sqrt(3.0);
  for (std::size_t v = 0; v < m.points.size(); v += kVerticesPerHexagon) {
    // The fan's triangles are (c0 c1 c2) (c0 c2 c3) (c0 c3 c4) (c0 c4 c5): c0 and c3 are opposite
    // corners, and the cell's centre lies halfway between them.
    const Eigen::Vector2d corner0(m.points[v].x, m.points[v].y);
    const Eigen::Vector2d corner3(m.points[v + 5].x, m.points[v + 5].y);
    const Eigen::Vector2d centre = 0.5 * (corner0 + corner3);
    const auto cell = grid.lattice().CellOf(centre);
    EXPECT_NEAR((grid.lattice().CentreOf(cell) - centre).norm(), 0.0, 1e-9);
    EXPECT_NEAR((corner0 - centre).norm(), 0.9 * circumradius, 1e-9);
    EXPECT_NE(grid.LogOdds(cell), 0.0f);
    EXPECT_FLOAT_EQ(m.colors[v].r, 1.0f - grid.Probability(cell));
    EXPECT_DOUBLE_EQ(m.points[v].z, MarkerStyle().height);
  }
  // The wall is dark, the free space before it light.
  bool saw_dark = false, saw_light = false;
  for (const auto& c : m.colors) {
    saw_dark |= c.r < 0.2f;
    saw_light |= c.r > 0.55f;  // one pass: p = 0.4
  }
  EXPECT_TRUE(saw_dark);
  EXPECT_TRUE(saw_light);
}

TEST(HexMapMarkerTest, SquareLatticeGetsSquaresAndTheCapHolds) {
  const GridMap<SquareLattice> grid = WallGrid<SquareLattice>();
  MarkerStyle style;
  style.max_cells = 10;
  MarkerStats stats;
  const visualization_msgs::Marker m =
      MakeHexMapMarker(grid.log_odds_grid(), style, "map", ros::Time(1), &stats);
  EXPECT_EQ(stats.known_cells, KnownCells(grid.log_odds_grid().values()));
  EXPECT_EQ(stats.drawn_cells, 10);
  EXPECT_EQ(m.points.size(), 10u * 2 * 3);  // two triangles a square
}

TEST(HexMapMarkerTest, AnEmptyMapDeletesTheMarker) {
  GridMap<HexLattice> grid(HexLattice(0.1), HectorModel(), GridGrowthPolicy(), Square(1.0));
  MarkerStats stats;
  const visualization_msgs::Marker m =
      MakeHexMapMarker(grid.log_odds_grid(), MarkerStyle(), "map", ros::Time(1), &stats);
  EXPECT_EQ(m.action, visualization_msgs::Marker::DELETE);
  EXPECT_TRUE(m.points.empty());
  EXPECT_EQ(stats.known_cells, 0);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
