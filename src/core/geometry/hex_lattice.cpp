#include "hex_slam/geometry/hex_lattice.h"

#include <cmath>
#include <stdexcept>

namespace hex_slam {

HexLattice::HexLattice(double spacing)
    : spacing_(spacing), cube_scale_(0.5 * kSqrt3 * spacing), inv_cube_scale_(1.0 / cube_scale_) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw std::invalid_argument("HexLattice: spacing must be positive and finite");
  }
}

void HexLattice::IndexBounds(const Eigen::AlignedBox2d& box, GridIndex* min,
                             GridIndex* max) const {
  // Column a sits at X = w·a; within a column rows are d apart, odd columns raised by d/2.
  min->col = FloorToInt(box.min().x() / cube_scale_) - 1;
  max->col = CeilToInt(box.max().x() / cube_scale_) + 1;
  min->row = FloorToInt(box.min().y() / spacing_) - 1;
  max->row = CeilToInt(box.max().y() / spacing_) + 1;
}

HexStencil HexLattice::Stencil(const Eigen::Vector3d& u) {
  int f[3] = {FloorToInt(u.x()), FloorToInt(u.y()), FloorToInt(u.z())};
  int sum = f[0] + f[1] + f[2];
  if (sum == 0) {
    // Exactly on a centre: use the s = -1 triangle that has this centre as its x corner.
    f[0] -= 1;
    sum = -1;
  }
  HexStencil st;
  const double frac[3] = {u.x() - f[0], u.y() - f[1], u.z() - f[2]};
  if (sum == -1) {
    st.gradient_sign = 1.0;
    st.cells[0] = {f[0] + 1, f[1]};
    st.cells[1] = {f[0], f[1] + 1};
    st.cells[2] = {f[0], f[1]};  // its c is f[2] + 1
    for (int k = 0; k < 3; ++k) st.weights[k] = frac[k];
  } else {
    st.gradient_sign = -1.0;
    st.cells[0] = {f[0], f[1] + 1};      // (f + 1 - e_x): c = f[2] + 1
    st.cells[1] = {f[0] + 1, f[1]};      // (f + 1 - e_y): c = f[2] + 1
    st.cells[2] = {f[0] + 1, f[1] + 1};  // (f + 1 - e_z): c = f[2]
    for (int k = 0; k < 3; ++k) st.weights[k] = 1.0 - frac[k];
  }
  return st;
}

}  // namespace hex_slam
