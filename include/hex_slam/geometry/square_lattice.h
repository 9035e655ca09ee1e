// The square lattice of hector_mapping, kept as the baseline (MATH.md §8): cell (i, j) is centred
// at (i·s, j·s) and covers [i - 1/2, i + 1/2)·s × [j - 1/2, j + 1/2)·s.
#ifndef HEX_SLAM_GEOMETRY_SQUARE_LATTICE_H_
#define HEX_SLAM_GEOMETRY_SQUARE_LATTICE_H_

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/geometry/grid_index.h"

namespace hex_slam {

class SquareLattice {
 public:
  using Cell = GridIndex;
  static constexpr const char* kName = "square";

  explicit SquareLattice(double side);

  double spacing() const { return side_; }
  double cell_area() const { return side_ * side_; }
  // How far a cell's corners lie from its centre: no point of the cell lies farther.
  double circumradius() const { return side_ * M_SQRT1_2; }

  Cell CellOf(const Eigen::Vector2d& world) const {
    return {FloorToInt(world.x() * inv_side_ + 0.5), FloorToInt(world.y() * inv_side_ + 0.5)};
  }
  Eigen::Vector2d CentreOf(const Cell& cell) const { return {side_ * cell.col, side_ * cell.row}; }
  static GridIndex ToIndex(const Cell& cell) { return cell; }
  static Cell FromIndex(const GridIndex& index) { return index; }

  void IndexBounds(const Eigen::AlignedBox2d& box, GridIndex* min, GridIndex* max) const;

  double inv_side() const { return inv_side_; }

 private:
  double side_;
  double inv_side_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_SQUARE_LATTICE_H_
