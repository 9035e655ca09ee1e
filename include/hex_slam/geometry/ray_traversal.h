// Exact ray traversal: every cell a segment crosses, in order, visited once.
//
// Both functions fill `crossed` with the cells from the one containing `from` up to, but not
// including, the cell containing `to` (the caller marks that one occupied): an endpoint is never
// returned as free space.
#ifndef HEX_SLAM_GEOMETRY_RAY_TRAVERSAL_H_
#define HEX_SLAM_GEOMETRY_RAY_TRAVERSAL_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {

void TraceRay(const HexLattice& lattice, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
              std::vector<HexCell>* crossed);

void TraceRay(const SquareLattice& lattice, const Eigen::Vector2d& from,
              const Eigen::Vector2d& to, std::vector<GridIndex>* crossed);

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_RAY_TRAVERSAL_H_
