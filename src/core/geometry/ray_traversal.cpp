#include "hex_slam/geometry/ray_traversal.h"

#include "geometry/ray_walk.h"

namespace hex_slam {
namespace {

template <class Lattice>
void Collect(const Lattice& lattice, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
             std::vector<typename Lattice::Cell>* crossed) {
  crossed->clear();
  WalkRay(lattice, from, lattice.CellOf(from), to, lattice.CellOf(to),
          [crossed](const typename Lattice::Cell& cell) { crossed->push_back(cell); });
}

}  // namespace

void TraceRay(const HexLattice& lattice, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
              std::vector<HexCell>* crossed) {
  Collect(lattice, from, to, crossed);
}

void TraceRay(const SquareLattice& lattice, const Eigen::Vector2d& from,
              const Eigen::Vector2d& to, std::vector<GridIndex>* crossed) {
  Collect(lattice, from, to, crossed);
}

}  // namespace hex_slam
