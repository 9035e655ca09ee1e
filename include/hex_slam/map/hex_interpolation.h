// Occupancy value and gradient anywhere on the hex map, from the three nearest centres (MATH.md §4).
//
// The gradient is the in-plane one: derivatives per metre of cube-space coordinate, with zero
// component along (1, 1, 1). The paper's per-axis partials are 3/2 larger; see MATH.md.
#ifndef HEX_SLAM_MAP_HEX_INTERPOLATION_H_
#define HEX_SLAM_MAP_HEX_INTERPOLATION_H_

#include <cmath>
#include <cstdint>

#include <Eigen/Core>

#include "hex_slam/geometry/grid_index.h"
#include "hex_slam/map/hex_grid.h"

namespace hex_slam {

struct HexSample {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};

// Storage offsets of the axial rhombus (a, b), (a+1, b), (a, b+1), (a+1, b+1); false when it
// is not wholly in storage. In odd-q storage it is two adjacent columns, so one bounds check
// covers all four cells.
struct HexRhombus {
  std::size_t o00, o10, o01, o11;
};
inline bool LocateHexRhombus(const GridRect& rect, int a, int b, HexRhombus* r) {
  const GridIndex base = HexLattice::ToIndex(HexCell{a, b});
  const int odd = a & 1;  // column a+1 sits half a row higher in storage when a is odd
  const int col = base.col - rect.min.col;
  const int row = base.row - rect.min.row;
  if (!(col >= 0 && col + 1 < rect.width && row >= 0 && row + 2 < rect.height)) return false;
  r->o00 = static_cast<std::size_t>(row) * rect.width + col;
  r->o01 = r->o00 + rect.width;
  r->o10 = r->o00 + 1 + odd * rect.width;
  r->o11 = r->o10 + rect.width;
  return true;
}

// The interpolant as a function of the lattice-unit cube coordinates u_x and u_y alone (u_ζ
// follows from the plane): its value and its partial derivatives along them. The in-plane
// gradient g (MATH.md §4) follows as g_x = (2 d_x - d_y) / 3, g_y = (2 d_y - d_x) / 3,
// g_ζ = -(d_x + d_y) / 3; the matcher accumulates in these partials, which cost fewer operations
// per point, and converts its sums once.
struct HexPartials {
  double value = 0.0;
  double du_x = 0.0;
  double du_y = 0.0;
};

// The interpolation inside the rhombus (a, b), (a+1, b), (a, b+1), (a+1, b+1) with probabilities
// m00, m10, m01, m11, at fractional parts (wx, wy) (see InterpolateHexLatticeUnits). The lower
// triangle's plane is m00 + wx (m10 - m00) + wy (m01 - m00); the upper one's differs from it by
// q (wx + wy - 1), q = m11 - m10 - m01 + m00, which vanishes on the shared edge. Which triangle a
// point falls in is a coin flip, so `upper` enters as a 0/1 factor rather than a branch (one
// would mispredict half the time in the matcher's loop; the int keeps gcc from making one).
inline HexPartials BlendHexRhombus(double m00, double m10, double m01, double m11, double wx,
                                   double wy) {
  const int upper = wx + wy > 1.0;
  const double d10 = m10 - m00, d01 = m01 - m00;
  const double tq = static_cast<double>(upper) * (m11 - m10 - d01);
  HexPartials out;
  out.value = m00 + wx * d10 + wy * d01 + tq * (wx + wy - 1.0);
  out.du_x = d10 + tq;
  out.du_y = d01 + tq;
  return out;
}

// `ux`, `uy` are a point's x and y cube coordinates divided by w, the matcher's working units.
//
// With a = floor(u_x), b = floor(u_y) and fractional parts wx, wy, both candidate triangles use
// cells of the axial rhombus (a, b), (a+1, b), (a, b+1), (a+1, b+1). Since u_x + u_y + u_ζ = 0,
// the fractional parts sum to -(f_x + f_y + f_ζ), so s = -1 exactly when wx + wy <= 1 and no
// third floor is needed:
//   s = -1: P = f + e_k      -> (a+1, b), (a, b+1), (a, b);      weights wx, wy, 1 - wx - wy
//   s = -2: P = f + 1 - e_k  -> (a, b+1), (a+1, b), (a+1, b+1);  weights 1 - wx, 1 - wy, wx+wy-1
inline HexPartials InterpolateHexPartials(const HexGrid& grid, double ux, double uy) {
  const int a = FloorToInt(ux);
  const int b = FloorToInt(uy);
  HexRhombus r;
  if (LocateHexRhombus(grid.rect(), a, b, &r)) {
    // The blend of centred probabilities, plus the constant they are centred on: the weights
    // sum to one, and the partials do not see a constant.
    const float* c = grid.centred_probabilities();
    HexPartials out = BlendHexRhombus(c[r.o00], c[r.o10], c[r.o01], c[r.o11], ux - a, uy - b);
    out.value += HexGrid::kUnknownProbability;
    return out;
  }
  // At the storage's edge: unknown outside; the same arithmetic as inside, so that a reading
  // does not depend on where the storage happens to end.
  const auto centred = [&grid](int x, int y) {
    return grid.CentredAt(HexLattice::ToIndex(HexCell{x, y}));
  };
  HexPartials out = BlendHexRhombus(centred(a, b), centred(a + 1, b), centred(a, b + 1),
                                    centred(a + 1, b + 1), ux - a, uy - b);
  out.value += HexGrid::kUnknownProbability;
  return out;
}

// The same with the in-plane gradient, per lattice unit.
inline HexSample InterpolateHexLatticeUnits(const HexGrid& grid, double ux, double uy) {
  const HexPartials p = InterpolateHexPartials(grid, ux, uy);
  HexSample out;
  out.value = p.value;
  out.gradient = Eigen::Vector3d(2.0 * p.du_x - p.du_y, 2.0 * p.du_y - p.du_x,
                                 -(p.du_x + p.du_y)) * (1.0 / 3.0);
  return out;
}

// The sub-cell offset inside rhombus `r` at fractional parts (wx, wy), in lattice units (cube x
// and y over w): MeanHitOffset over the interpolation stencil. False where none of its cells was
// hit.
inline bool HexRhombusHitOffset(const HexGrid& grid, const std::uint32_t* slot,
                                const HexRhombus& r, double wx, double wy, double* ox,
                                double* oy) {
  // MeanHitOffset's three sums over the corners of BlendHexRhombus's triangle, in the float lanes
  // (weight, x, y, count) of their records; the corners picked by arithmetic on the 0/1 `upper`
  // (size_t arithmetic wraps and comes back exactly), for the reason given there.
  const std::size_t upper = wx + wy > 1.0;
  const float t = static_cast<float>(upper);
  const CellHits* h = grid.hit_records();
  using Record = Eigen::Map<const Eigen::Array4f, Eigen::Aligned16>;
  const Record cx(&h[slot[r.o10 + upper * (r.o01 - r.o10)]].weight);
  const Record cy(&h[slot[r.o01 + upper * (r.o10 - r.o01)]].weight);
  const Record cz(&h[slot[r.o00 + upper * (r.o11 - r.o00)]].weight);
  const float fx = static_cast<float>(wx), fy = static_cast<float>(wy);
  const float ex = fx + t * (1.0f - 2.0f * fx), ey = fy + t * (1.0f - 2.0f * fy);
  const Eigen::Array4f sum = ex * cx + ey * cy + (1.0f - ex - ey) * cz;
  if (sum[0] <= kMinHitWeight) return false;
  const float inv_total = 1.0f / sum[0];
  const double mx = sum[1] * inv_total, my = sum[2] * inv_total;  // metres, world axes
  const double inv_w = grid.lattice().inv_cube_scale();
  *ox = mx * inv_w;
  *oy = (-0.5 * mx + 0.5 * kSqrt3 * my) * inv_w;
  return true;
}

// The sub-cell offset at (ux, uy), in lattice units. Zero where none of the stencil's cells was
// hit.
inline void HexHitOffset(const HexGrid& grid, double ux, double uy, double* ox, double* oy) {
  *ox = *oy = 0.0;
  const int a = FloorToInt(ux), b = FloorToInt(uy);
  HexRhombus r;
  if (LocateHexRhombus(grid.rect(), a, b, &r)) {
    HexRhombusHitOffset(grid, grid.hit_slots(), r, ux - a, uy - b, ox, oy);
    return;
  }
  // At the storage's edge: the cells outside were never hit (slot 0), the rest are read one by
  // one, so the offset does not depend on where the storage happens to end.
  const HexCell cells[4] = {{a, b}, {a + 1, b}, {a, b + 1}, {a + 1, b + 1}};
  std::uint32_t slots[4];
  for (int k = 0; k < 4; ++k) slots[k] = grid.HitSlotAt(HexLattice::ToIndex(cells[k]));
  HexRhombusHitOffset(grid, slots, HexRhombus{0, 1, 2, 3}, ux - a, uy - b, ox, oy);
}

// Sub-cell interpolation: the map read at the point moved back by the local hit offset, so the
// occupancy peaks where the walls were seen, not at the centres of their cells. The gradient is
// that of the moved map (the offset is treated as locally constant, which it is along a wall).
inline HexSample InterpolateHexSubcellLatticeUnits(const HexGrid& grid, double ux, double uy) {
  double ox, oy;
  HexHitOffset(grid, ux, uy, &ox, &oy);
  return InterpolateHexLatticeUnits(grid, ux - ox, uy - oy);
}

// A lattice-unit interpolation read at a point in metres of cube space; gradient per metre.
template <HexSample (*Interpolate)(const HexGrid&, double, double)>
HexSample InterpolateHexInMetres(const HexGrid& grid, const Eigen::Vector3d& cube_point) {
  const double inv_w = grid.lattice().inv_cube_scale();
  HexSample out = Interpolate(grid, cube_point.x() * inv_w, cube_point.y() * inv_w);
  out.gradient *= inv_w;
  return out;
}

// `cube_point` in metres of cube space (CartesianToCube of a world point); gradient per metre.
inline HexSample InterpolateHex(const HexGrid& grid, const Eigen::Vector3d& cube_point) {
  return InterpolateHexInMetres<InterpolateHexLatticeUnits>(grid, cube_point);
}
inline HexSample InterpolateHexSubcell(const HexGrid& grid, const Eigen::Vector3d& cube_point) {
  return InterpolateHexInMetres<InterpolateHexSubcellLatticeUnits>(grid, cube_point);
}

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_HEX_INTERPOLATION_H_
