#include "hex_slam/geometry/square_lattice.h"

#include <stdexcept>

namespace hex_slam {

SquareLattice::SquareLattice(double side) : side_(side), inv_side_(1.0 / side) {
  if (!(side > 0.0) || !std::isfinite(side)) {
    throw std::invalid_argument("SquareLattice: side must be positive and finite");
  }
}

void SquareLattice::IndexBounds(const Eigen::AlignedBox2d& box, GridIndex* min,
                                GridIndex* max) const {
  min->col = FloorToInt(box.min().x() * inv_side_) - 1;
  max->col = CeilToInt(box.max().x() * inv_side_) + 1;
  min->row = FloorToInt(box.min().y() * inv_side_) - 1;
  max->row = CeilToInt(box.max().y() * inv_side_) + 1;
}

}  // namespace hex_slam
