// The hexagonal lattice of MATH.md §2: flat-top cells whose centres are w·(a, b, c) in cube space,
// neighbours at distance d = 2w/sqrt(3). Stored "odd-q": column a, row b + floor(a/2), so a dense
// rectangle of storage covers a Cartesian rectangle without waste.
#ifndef HEX_SLAM_GEOMETRY_HEX_LATTICE_H_
#define HEX_SLAM_GEOMETRY_HEX_LATTICE_H_

#include <algorithm>
#include <cstdlib>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/geometry/cube.h"
#include "hex_slam/geometry/grid_index.h"

namespace hex_slam {

// The six neighbour steps in axial coordinates (a, b), in the order of their Cartesian
// directions (flat-top cells): -30°, 30°, 90°, 150°, 210°, 270°.
constexpr int kHexNeighbourDa[6] = {1, 1, 0, -1, -1, 0};
constexpr int kHexNeighbourDb[6] = {-1, 0, 1, 1, 0, -1};

// Steps between two cells: the hex distance max(|Δa|, |Δb|, |Δc|).
inline int HexDistance(const HexCell& x, const HexCell& y) {
  return std::max({std::abs(x.a - y.a), std::abs(x.b - y.b), std::abs(x.c() - y.c())});
}

// The three lattice points around a continuous point and their interpolation weights
// (MATH.md §4). gradient_sign is +1 for the "s = -1" triangle and -1 for "s = -2".
struct HexStencil {
  HexCell cells[3];
  double weights[3];
  double gradient_sign;
};

class HexLattice {
 public:
  using Cell = HexCell;
  static constexpr const char* kName = "hex";

  // `spacing` is d, the distance between neighbouring centres (the public map_resolution).
  explicit HexLattice(double spacing);

  double spacing() const { return spacing_; }
  // w: the scale of a lattice point in cube space.
  double cube_scale() const { return cube_scale_; }
  double cell_area() const { return 0.5 * kSqrt3 * spacing_ * spacing_; }
  // How far a cell's corners lie from its centre: no point of the cell lies farther.
  double circumradius() const { return spacing_ / kSqrt3; }
  // The spacing whose hexagon has the area of a square of side `square_side`.
  static double SpacingForArea(double area) { return std::sqrt(2.0 * area / kSqrt3); }

  Cell CellOf(const Eigen::Vector2d& world) const {
    return RoundCube(CartesianToCube(world.x(), world.y()) * inv_cube_scale_);
  }
  Eigen::Vector2d CentreOf(const Cell& cell) const {
    return {cube_scale_ * cell.a, 0.5 * spacing_ * (cell.a + 2 * cell.b)};
  }
  static GridIndex ToIndex(const Cell& cell) { return {cell.a, cell.b + FloorHalf(cell.a)}; }
  static Cell FromIndex(const GridIndex& index) {
    return {index.col, index.row - FloorHalf(index.col)};
  }
  Eigen::Vector2d CentreOf(const GridIndex& index) const { return CentreOf(FromIndex(index)); }

  // The storage rectangle [min, max] whose cells cover `box`.
  void IndexBounds(const Eigen::AlignedBox2d& box, GridIndex* min, GridIndex* max) const;

  // Weights of the three nearest centres around `u`, a cube point in lattice units.
  static HexStencil Stencil(const Eigen::Vector3d& u);

  double inv_cube_scale() const { return inv_cube_scale_; }

 private:
  double spacing_;
  double cube_scale_;
  double inv_cube_scale_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_HEX_LATTICE_H_
