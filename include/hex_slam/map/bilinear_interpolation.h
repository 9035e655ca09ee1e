// Occupancy value and Cartesian gradient on the square map: hector_mapping's bilinear scheme over
// the four centres around a point.
#ifndef HEX_SLAM_MAP_BILINEAR_INTERPOLATION_H_
#define HEX_SLAM_MAP_BILINEAR_INTERPOLATION_H_

#include <cmath>
#include <cstdint>

#include <Eigen/Core>

#include "hex_slam/geometry/grid_index.h"
#include "hex_slam/map/square_grid.h"

namespace hex_slam {

struct SquareSample {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();  // per metre
};

inline SquareSample InterpolateBilinear(const SquareGrid& grid, const Eigen::Vector2d& world) {
  const double inv_s = grid.lattice().inv_side();
  const double ux = world.x() * inv_s;
  const double uy = world.y() * inv_s;
  const int i = FloorToInt(ux);
  const int j = FloorToInt(uy);
  const double tx = ux - i;
  const double ty = uy - j;
  double m00, m10, m01, m11;
  const GridRect& rect = grid.rect();
  const int col = i - rect.min.col;
  const int row = j - rect.min.row;
  constexpr double kCentre = SquareGrid::kUnknownProbability;
  if (col >= 0 && col + 1 < rect.width && row >= 0 && row + 1 < rect.height) {
    const float* c =
        grid.centred_probabilities() + static_cast<std::size_t>(row) * rect.width + col;
    m00 = kCentre + c[0];
    m10 = kCentre + c[1];
    m01 = kCentre + c[rect.width];
    m11 = kCentre + c[rect.width + 1];
  } else {  // at the storage's edge: unknown outside, the same arithmetic as inside
    m00 = kCentre + grid.CentredAt({i, j});
    m10 = kCentre + grid.CentredAt({i + 1, j});
    m01 = kCentre + grid.CentredAt({i, j + 1});
    m11 = kCentre + grid.CentredAt({i + 1, j + 1});
  }
  SquareSample out;
  out.value = (1.0 - ty) * ((1.0 - tx) * m00 + tx * m10) + ty * ((1.0 - tx) * m01 + tx * m11);
  out.gradient.x() = ((1.0 - ty) * (m10 - m00) + ty * (m11 - m01)) * inv_s;
  out.gradient.y() = ((1.0 - tx) * (m01 - m00) + tx * (m11 - m10)) * inv_s;
  return out;
}

// The sub-cell offset at `world` (m): MeanHitOffset over the four cells around it. Zero where
// none of them was hit.
inline Eigen::Vector2d SquareHitOffset(const SquareGrid& grid, const Eigen::Vector2d& world) {
  const double inv_s = grid.lattice().inv_side();
  const double ux = world.x() * inv_s, uy = world.y() * inv_s;
  const int i = FloorToInt(ux), j = FloorToInt(uy);
  const GridRect& rect = grid.rect();
  const int col = i - rect.min.col;
  const int row = j - rect.min.row;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  const double tx = ux - i, ty = uy - j;
  const double weights[4] = {(1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty};
  if (col >= 0 && col + 1 < rect.width && row >= 0 && row + 1 < rect.height) {
    const std::size_t o = static_cast<std::size_t>(row) * rect.width + col;
    const std::size_t cells[4] = {o, o + 1, o + rect.width, o + rect.width + 1};
    MeanHitOffset(grid.hit_records(), grid.hit_slots(), cells, weights, 4, &mean);
    return mean;
  }
  // At the storage's edge: the cells outside were never hit (slot 0), the rest are read one by
  // one, so the offset does not depend on where the storage happens to end.
  const GridIndex around[4] = {{i, j}, {i + 1, j}, {i, j + 1}, {i + 1, j + 1}};
  std::uint32_t slots[4];
  for (int k = 0; k < 4; ++k) slots[k] = grid.HitSlotAt(around[k]);
  const std::size_t cells[4] = {0, 1, 2, 3};
  MeanHitOffset(grid.hit_records(), slots, cells, weights, 4, &mean);
  return mean;
}

// Sub-cell interpolation: the map read at the point moved back by the local hit offset, so the
// occupancy peaks where the walls were seen (the same refinement as InterpolateHexSubcell).
inline SquareSample InterpolateBilinearSubcell(const SquareGrid& grid,
                                               const Eigen::Vector2d& world) {
  return InterpolateBilinear(grid, world - SquareHitOffset(grid, world));
}

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_BILINEAR_INTERPOLATION_H_
