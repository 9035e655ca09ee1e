// Every lattice seen as Z²: integer coordinates in which a translation by a lattice vector adds
// the same offset to every cell. On the square lattice they are (column, row); on the hex
// lattice the axial pair (a, b) of cube coordinates, not the odd-q storage index, whose row
// shifts with every other column. Window searches that slide a scan over the map by whole cells
// (branch and bound) work in these coordinates and are written once for both lattices.
#ifndef HEX_SLAM_MATCHING_LATTICE_AXES_H_
#define HEX_SLAM_MATCHING_LATTICE_AXES_H_

#include <cmath>

#include <Eigen/Core>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace matching {

template <class Lattice>
struct LatticeAxes;

template <>
struct LatticeAxes<HexLattice> {
  static Eigen::Array2i Of(const HexCell& cell) { return {cell.a, cell.b}; }
  static HexCell CellAt(const Eigen::Array2i& z) { return {z.x(), z.y()}; }
  // Columns: the world displacement of one step along a, and along b (cell centres are
  // (w·a, d/2·(a + 2b)), HexLattice::CentreOf).
  static Eigen::Matrix2d Basis(const HexLattice& lattice) {
    Eigen::Matrix2d basis;
    basis << lattice.cube_scale(), 0.0,
             0.5 * lattice.spacing(), lattice.spacing();
    return basis;
  }
};

template <>
struct LatticeAxes<SquareLattice> {
  static Eigen::Array2i Of(const GridIndex& cell) { return {cell.col, cell.row}; }
  static GridIndex CellAt(const Eigen::Array2i& z) { return {z.x(), z.y()}; }
  static Eigen::Matrix2d Basis(const SquareLattice& lattice) {
    return Eigen::Matrix2d::Identity() * lattice.spacing();
  }
};

// The smallest box of lattice offsets whose translations cover every translation in
// [-half_width, half_width]² (m): on the hex lattice an axial parallelogram around that square.
inline Eigen::Array2i OffsetsCovering(const Eigen::Matrix2d& basis, double half_width) {
  const Eigen::Matrix2d inverse = basis.inverse();
  return {static_cast<int>(std::ceil(half_width * inverse.row(0).cwiseAbs().sum())),
          static_cast<int>(std::ceil(half_width * inverse.row(1).cwiseAbs().sum()))};
}

}  // namespace matching
}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_LATTICE_AXES_H_
