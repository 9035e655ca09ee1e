#include "hex_slam/matching/precomputation_grid.h"

#include <algorithm>
#include <cstddef>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/lattice_axes.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace matching {

PrecomputationGrid::PrecomputationGrid(const Eigen::Array2i& origin, const Eigen::Array2i& size,
                                       float outside)
    : origin_(origin),
      size_(size.max(0)),
      outside_(outside),
      values_(static_cast<std::size_t>(size_.x()) * size_.y(), outside) {}

PrecomputationGrid PrecomputationGrid::Doubled(int half) const {
  // A window of 2·half cells starting at z meets a known cell only if z lies within
  // 2·half - 1 cells before the known box: the box grows by that much towards lower coordinates
  // (by `half` against this depth's box, which already grew by half - 1).
  PrecomputationGrid out(origin_ - half, size_ + half, outside_);
  // The window's maximum is taken along rows first (each row against itself `half` cells on),
  // then between rows `half` apart: the same maximum of the same four cells as cell by cell,
  // in straight loops over contiguous rows instead of four bounds-checked reads per cell.
  const int width = out.size_.x();
  std::vector<float> row_pairs(static_cast<std::size_t>(size_.y()) * width);
  std::vector<float> padded(static_cast<std::size_t>(width) + half, outside_);
  for (int row = 0; row < size_.y(); ++row) {
    // padded[half + x] is this row's cell x; outside the row, `outside_`.
    std::copy_n(values_.begin() + static_cast<std::ptrdiff_t>(row) * size_.x(), size_.x(),
                padded.begin() + half);
    float* pairs = row_pairs.data() + static_cast<std::size_t>(row) * width;
    for (int x = 0; x < width; ++x) pairs[x] = std::max(padded[x], padded[x + half]);
  }
  const std::vector<float> outside_row(width, outside_);
  const auto pairs_of = [&](int row) {
    return row >= 0 && row < size_.y() ? row_pairs.data() + static_cast<std::size_t>(row) * width
                                       : outside_row.data();
  };
  for (int y = 0; y < out.size_.y(); ++y) {
    const float* lower = pairs_of(y - half);
    const float* upper = pairs_of(y);
    float* target = out.values_.data() + static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x) target[x] = std::max(lower[x], upper[x]);
  }
  return out;
}

template <class Lattice>
PrecomputationGridStack::PrecomputationGridStack(const GridMap<Lattice>& grid, int max_depth,
                                                 float unknown_value) {
  using Axes = LatticeAxes<Lattice>;
  // The box of known cells in lattice coordinates (on the hex lattice the storage rectangle is
  // not a box of axial coordinates, so it is found cell by cell).
  // Only the written part of the storage is visited: a submap reserves far more than it fills.
  const LogOddsGrid<Lattice>& log_odds = grid.log_odds_grid();
  Eigen::Array2i lo(0, 0), hi(-1, -1);
  bool any = false;
  log_odds.ForEachKnown([&](std::size_t, const GridIndex& index, float) {
    const Eigen::Array2i z = Axes::Of(Lattice::FromIndex(index));
    lo = any ? lo.min(z) : z;
    hi = any ? hi.max(z) : z;
    any = true;
  });
  PrecomputationGrid cells(lo, hi - lo + 1, unknown_value);
  log_odds.ForEachKnown([&](std::size_t, const GridIndex& index, float) {
    cells.Set(Axes::Of(Lattice::FromIndex(index)), grid.ProbabilityAt(index));
  });
  grids_.push_back(std::move(cells));
  for (int depth = 1; depth <= max_depth; ++depth) {
    grids_.push_back(grids_.back().Doubled(1 << (depth - 1)));
  }
}

std::size_t PrecomputationGridStack::MemoryBytes() const {
  std::size_t bytes = 0;
  for (const PrecomputationGrid& g : grids_) bytes += g.MemoryBytes();
  return bytes;
}

template PrecomputationGridStack::PrecomputationGridStack(const GridMap<HexLattice>&, int, float);
template PrecomputationGridStack::PrecomputationGridStack(const GridMap<SquareLattice>&, int,
                                                          float);

}  // namespace matching
}  // namespace hex_slam
