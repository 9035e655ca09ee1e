// Occupancy value and gradient anywhere on the hex map, from the three nearest centres (MATH.md §4).
//
// The gradient is the in-plane one: derivatives per metre of cube-space coordinate, with zero
// component along (1, 1, 1). The paper's per-axis partials are 3/2 larger; see MATH.md.
#ifndef HEX_SLAM_HEX_INTERPOLATION_H_
#define HEX_SLAM_HEX_INTERPOLATION_H_

#include <Eigen/Core>

#include "hex_slam/hex_grid.h"

namespace hex_slam {

struct HexSample {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};

// `cube_point` in metres of cube space (CartesianToCube of a world point).
inline HexSample InterpolateHex(const HexGrid& grid, const Eigen::Vector3d& cube_point) {
  const double inv_w = grid.lattice().inv_cube_scale();
  const HexStencil st = HexLattice::Stencil(cube_point * inv_w);
  double m[3];
  for (int k = 0; k < 3; ++k) m[k] = grid.Probability(st.cells[k]);
  HexSample out;
  out.value = st.weights[0] * m[0] + st.weights[1] * m[1] + st.weights[2] * m[2];
  const double mean = (m[0] + m[1] + m[2]) / 3.0;
  const double scale = st.gradient_sign * inv_w;
  out.gradient = Eigen::Vector3d(m[0] - mean, m[1] - mean, m[2] - mean) * scale;
  return out;
}

}  // namespace hex_slam

#endif  // HEX_SLAM_HEX_INTERPOLATION_H_
