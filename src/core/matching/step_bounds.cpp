#include "hex_slam/matching/step_bounds.h"

#include <algorithm>
#include <cstdint>
#include <vector>

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

// One storage row's raises of the cells whose centres lie at height `y`: of the pixel rows
// [y_from, y_to], gathered along x (from the box's first pixel). A row's cells span the box.
struct RowSpanCodes {
  double y = 0.0;
  int y_from = 0, y_to = 0;
  std::vector<std::uint8_t> codes;
};

// The gathered raises of the cells at height `y` among the first *used of `spans` (reused
// between rows), a cleared one appended when none is: its pixel rows are those within
// `cell_reach` of y, within [lowest, highest].
RowSpanCodes& SpanOf(double y, double cell_reach, double pixel, int lowest, int highest,
                     int width, std::vector<RowSpanCodes>* spans, std::size_t* used) {
  for (std::size_t i = 0; i < *used; ++i) {
    if ((*spans)[i].y == y) return (*spans)[i];
  }
  if (*used == spans->size()) spans->emplace_back();
  RowSpanCodes& span = (*spans)[(*used)++];
  span.y = y;
  span.y_from = std::max(PixelIndexOf(y - cell_reach, pixel), lowest);
  span.y_to = std::min(PixelIndexOf(y + cell_reach, pixel), highest);
  span.codes.assign(static_cast<std::size_t>(width), 0);
  return span;
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
  // The same pixels as raising each cell's rectangle in turn, in a fraction of the time (this was
  // the search's largest cost without odometry). A storage row's centres lie at one height on the
  // square lattice and at two on the hex lattice (odd columns half a spacing higher): each
  // height's raises are gathered along x first, then laid over its pixel rows a row at a time.
  // On both lattices a storage column keeps one x, so its pixel columns are found once.
  std::vector<Eigen::Array2i> columns;  // per column: its first and last pixel x, from lo.x()
  for (int col = first.col; col <= last.col; ++col) {
    const double x = lattice.CentreOf(GridIndex{col, first.row}).x();
    columns.emplace_back(std::max(PixelIndexOf(x - cell_reach, pixel), lo.x()) - lo.x(),
                         std::min(PixelIndexOf(x + cell_reach, pixel), hi.x()) - lo.x());
  }
  std::vector<RowSpanCodes> spans;
  const int width = bounds.size().x();
  for (int row = first.row; row <= last.row; ++row) {
    std::size_t used = 0;
    for (int col = first.col; col <= last.col; ++col) {
      const Eigen::Array2i& xs = columns[col - first.col];
      if (xs[0] > xs[1]) continue;
      const GridIndex index{col, row};
      RowSpanCodes& span = SpanOf(lattice.CentreOf(index).y(), cell_reach, pixel, lo.y(), hi.y(),
                                  width, &spans, &used);
      if (span.y_from > span.y_to) continue;
      const std::uint8_t code = QuantizeValueUp(grid.ProbabilityAt(index));
      for (int x = xs[0]; x <= xs[1]; ++x) span.codes[x] = std::max(span.codes[x], code);
    }
    for (std::size_t i = 0; i < used; ++i) {
      const RowSpanCodes& span = spans[i];
      for (int y = span.y_from; y <= span.y_to; ++y) {
        bounds.RaiseRow(y, lo.x(), span.codes.data(), width);
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
