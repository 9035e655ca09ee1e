#include "hex_slam/matching/step_bounds.h"

#include <algorithm>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace matching {
namespace {

// How far outside its pixel a point may lie and still be bounded by it (m): far more than the
// rounding of a coordinate kilometres out, far less than a cell.
constexpr double kPixelSlack = 1e-6;

// The world box holding every point of every cell of `rect`: on the hex lattice a storage row
// zigzags by half a cell, so the corner cells' centres are widened by a whole spacing.
template <class Lattice>
Eigen::AlignedBox2d WorldBoxOf(const Lattice& lattice, const GridRect& rect) {
  Eigen::AlignedBox2d box;
  const GridIndex lo = rect.min, hi = rect.max();
  for (const GridIndex& corner : {lo, hi, GridIndex{lo.col, hi.row}, GridIndex{hi.col, lo.row}}) {
    box.extend(lattice.CentreOf(corner));
  }
  const double widen = lattice.spacing() + lattice.circumradius();
  return Eigen::AlignedBox2d((box.min().array() - widen).matrix(),
                             (box.max().array() + widen).matrix());
}

}  // namespace

template <class Lattice>
Eigen::AlignedBox2d BoundedBox(const GridMap<Lattice>& grid, const Eigen::AlignedBox2d& reach) {
  const GridRect& written = grid.log_odds_grid().written();
  return written.empty() ? Eigen::AlignedBox2d()
                         : WorldBoxOf(grid.lattice(), written).intersection(reach);
}

template <class Lattice>
PrecomputationGrid PixelBounds(const GridMap<Lattice>& grid, double pixel,
                               const Eigen::AlignedBox2d& reach) {
  const float unknown = GridMap<Lattice>::kUnknownProbability;
  const Lattice& lattice = grid.lattice();
  const Eigen::AlignedBox2d box = BoundedBox(grid, reach);
  if (box.isEmpty()) return PrecomputationGrid({0, 0}, {0, 0}, unknown);
  const Eigen::Array2i lo = PixelOf(box.min(), pixel), hi = PixelOf(box.max(), pixel);
  PrecomputationGrid bounds(lo, hi - lo + 1, unknown);
  bounds.Clear();
  // Each cell raises every pixel within its circumradius (and the slack) along both axes: a
  // superset of the pixels it meets. Every cell that can meet a pixel of the box is visited,
  // the unknown ones around the written part too.
  const double cell_reach = lattice.circumradius() + 2.0 * kPixelSlack;
  GridIndex first, last;
  lattice.IndexBounds(Eigen::AlignedBox2d((box.min().array() - cell_reach - pixel).matrix(),
                                          (box.max().array() + cell_reach + pixel).matrix()),
                      &first, &last);
  for (int row = first.row; row <= last.row; ++row) {
    for (int col = first.col; col <= last.col; ++col) {
      const GridIndex index{col, row};
      const Eigen::Vector2d centre = lattice.CentreOf(index);
      const Eigen::Array2i from = PixelOf((centre.array() - cell_reach).matrix(), pixel).max(lo);
      const Eigen::Array2i to = PixelOf((centre.array() + cell_reach).matrix(), pixel).min(hi);
      const float probability = grid.ProbabilityAt(index);
      for (int y = from.y(); y <= to.y(); ++y) {
        for (int x = from.x(); x <= to.x(); ++x) bounds.RaiseTo({x, y}, probability);
      }
    }
  }
  return bounds;
}

template Eigen::AlignedBox2d BoundedBox(const GridMap<HexLattice>&, const Eigen::AlignedBox2d&);
template Eigen::AlignedBox2d BoundedBox(const GridMap<SquareLattice>&,
                                        const Eigen::AlignedBox2d&);
template PrecomputationGrid PixelBounds(const GridMap<HexLattice>&, double,
                                        const Eigen::AlignedBox2d&);
template PrecomputationGrid PixelBounds(const GridMap<SquareLattice>&, double,
                                        const Eigen::AlignedBox2d&);

}  // namespace matching
}  // namespace hex_slam
