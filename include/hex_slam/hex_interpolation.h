// Occupancy value and gradient anywhere on the hex map, from the three nearest centres (MATH.md §4).
//
// The gradient is the in-plane one: derivatives per metre of cube-space coordinate, with zero
// component along (1, 1, 1). The paper's per-axis partials are 3/2 larger; see MATH.md.
#ifndef HEX_SLAM_HEX_INTERPOLATION_H_
#define HEX_SLAM_HEX_INTERPOLATION_H_

#include <cmath>

#include <Eigen/Core>

#include "hex_slam/grid_index.h"
#include "hex_slam/hex_grid.h"

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

// The probabilities of a rhombus: m00 = (a, b), m10 = (a+1, b), m01 = (a, b+1), m11 = (a+1, b+1).
struct HexRhombusValues {
  double m00, m10, m01, m11;
};
inline HexRhombusValues ReadHexRhombus(const HexGrid& grid, const HexRhombus& r) {
  const float* p = grid.probabilities().data();
  return {p[r.o00], p[r.o10], p[r.o01], p[r.o11]};
}

// The interpolation inside a rhombus at fractional parts (wx, wy) (see below), in lattice units.
inline HexSample BlendHexRhombus(const HexRhombusValues& m, double wx, double wy) {
  // Corners in (x, y, ζ) order, blended arithmetically: which triangle a point falls in is a coin
  // flip, and a branch on it mispredicts half the time in the matcher's inner loop.
  const double t = wx + wy > 1.0 ? 1.0 : 0.0;
  const double mx = m.m10 + t * (m.m01 - m.m10);
  const double my = m.m01 + t * (m.m10 - m.m01);
  const double mz = m.m00 + t * (m.m11 - m.m00);
  const double cx = wx + t * (1.0 - 2.0 * wx);  // weight of the x corner
  const double cy = wy + t * (1.0 - 2.0 * wy);
  HexSample out;
  out.value = mz + cx * (mx - mz) + cy * (my - mz);  // weights sum to 1
  const double sign = 1.0 - 2.0 * t;
  const double mean = (mx + my + mz) * (1.0 / 3.0);
  out.gradient = Eigen::Vector3d(mx - mean, my - mean, mz - mean) * sign;
  return out;
}

// The same in lattice units: `ux`, `uy` are a point's x and y cube coordinates divided by w
// (ζ follows from the plane), and the gradient comes out per lattice unit. The matcher's inner
// loop works here so that the scale by 1/w is applied once per scan, not per point.
//
// With a = floor(u_x), b = floor(u_y) and fractional parts wx, wy, both candidate triangles use
// cells of the axial rhombus (a, b), (a+1, b), (a, b+1), (a+1, b+1). Since u_x + u_y + u_ζ = 0,
// the fractional parts sum to -(f_x + f_y + f_ζ), so s = -1 exactly when wx + wy <= 1 and no
// third floor is needed:
//   s = -1: P = f + e_k      -> (a+1, b), (a, b+1), (a, b);      weights wx, wy, 1 - wx - wy
//   s = -2: P = f + 1 - e_k  -> (a, b+1), (a+1, b), (a+1, b+1);  weights 1 - wx, 1 - wy, wx+wy-1
inline HexSample InterpolateHexLatticeUnits(const HexGrid& grid, double ux, double uy) {
  const int a = FloorToInt(ux);
  const int b = FloorToInt(uy);
  HexRhombus r;
  const HexRhombusValues m =
      LocateHexRhombus(grid.rect(), a, b, &r)
          ? ReadHexRhombus(grid, r)
          : HexRhombusValues{grid.Probability(HexCell{a, b}), grid.Probability(HexCell{a + 1, b}),
                             grid.Probability(HexCell{a, b + 1}),
                             grid.Probability(HexCell{a + 1, b + 1})};
  return BlendHexRhombus(m, ux - a, uy - b);
}

// The sub-cell offset inside rhombus `r` at fractional parts (wx, wy), in lattice units (cube x
// and y over w): MeanHitOffset over the interpolation stencil. False where none of its cells was
// hit.
inline bool HexRhombusHitOffset(const HexGrid& grid, const HexRhombus& r, double wx, double wy,
                                double* ox, double* oy) {
  // The stencil of BlendHexRhombus: corners x, y, ζ of either triangle.
  const bool upper = wx + wy > 1.0;
  const std::size_t cells[3] = {upper ? r.o01 : r.o10, upper ? r.o10 : r.o01,
                                upper ? r.o11 : r.o00};
  const double weights[3] = {upper ? 1.0 - wx : wx, upper ? 1.0 - wy : wy,
                             upper ? wx + wy - 1.0 : 1.0 - wx - wy};
  Eigen::Vector2d mean;  // metres, world axes
  if (!MeanHitOffset(grid.probabilities().data(), grid.hits().data(), cells, weights, 3, &mean)) {
    return false;
  }
  const double inv_w = grid.lattice().inv_cube_scale();
  *ox = mean.x() * inv_w;
  *oy = (-0.5 * mean.x() + 0.5 * kSqrt3 * mean.y()) * inv_w;
  return true;
}

// The sub-cell offset at (ux, uy), in lattice units. Zero where none of the stencil's cells was
// hit.
inline void HexHitOffset(const HexGrid& grid, double ux, double uy, double* ox, double* oy) {
  *ox = *oy = 0.0;
  const int a = FloorToInt(ux), b = FloorToInt(uy);
  HexRhombus r;
  if (LocateHexRhombus(grid.rect(), a, b, &r)) HexRhombusHitOffset(grid, r, ux - a, uy - b, ox, oy);
}

// Sub-cell interpolation: the map read at the point moved back by the local hit offset, so the
// occupancy peaks where the walls were seen, not at the centres of their cells. The gradient is
// that of the moved map (the offset is treated as locally constant, which it is along a wall).
// Equal to InterpolateHexLatticeUnits(grid, ux - ox, uy - oy) with HexHitOffset's (ox, oy), but the
// rhombus is located and read once when the moved point stays in it.
inline HexSample InterpolateHexSubcellLatticeUnits(const HexGrid& grid, double ux, double uy) {
  const int a = FloorToInt(ux), b = FloorToInt(uy);
  HexRhombus r;
  if (!LocateHexRhombus(grid.rect(), a, b, &r)) return InterpolateHexLatticeUnits(grid, ux, uy);
  const double wx = ux - a, wy = uy - b;
  double ox, oy;
  if (!HexRhombusHitOffset(grid, r, wx, wy, &ox, &oy)) {
    return BlendHexRhombus(ReadHexRhombus(grid, r), wx, wy);
  }
  const double sx = ux - ox, sy = uy - oy;
  if (FloorToInt(sx) == a && FloorToInt(sy) == b) {
    return BlendHexRhombus(ReadHexRhombus(grid, r), sx - a, sy - b);
  }
  return InterpolateHexLatticeUnits(grid, sx, sy);
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

#endif  // HEX_SLAM_HEX_INTERPOLATION_H_
