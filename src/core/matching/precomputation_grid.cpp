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
      outside_(QuantizeValue(outside)),
      values_(static_cast<std::size_t>(size_.x()) * size_.y(), outside_) {}

PrecomputationGrid PrecomputationGrid::Doubled(int half) const {
  // A window of 2·half cells starting at z meets a known cell only if z lies within
  // 2·half - 1 cells before the known box: the box grows by that much towards lower coordinates
  // (by `half` against this depth's box, which already grew by half - 1).
  PrecomputationGrid out(origin_ - half, size_ + half, outside());
  // The window's maximum is taken along rows first (each row against itself `half` cells on),
  // then between rows `half` apart: the same maximum of the same four cells as cell by cell, in
  // straight loops over contiguous rows, within the output's own storage.
  const int width = out.size_.x();
  const int rows = out.size_.y();
  std::vector<std::uint8_t> padded(static_cast<std::size_t>(width) + half, outside_);
  const auto row_of = [&out, width](int y) -> std::uint8_t* {
    return out.values_.data() + static_cast<std::size_t>(y) * width;
  };
  // Output row y + half first holds this grid's row y paired along x (rows before `half`: none,
  // `outside_` as constructed); padded[half + x] is row y's cell x, `outside_` beyond it.
  for (int y = 0; y < size_.y(); ++y) {
    std::copy_n(values_.begin() + static_cast<std::ptrdiff_t>(y) * size_.x(), size_.x(),
                padded.begin() + half);
    std::uint8_t* pairs = row_of(y + half);
    for (int x = 0; x < width; ++x) pairs[x] = std::max(padded[x], padded[x + half]);
  }
  // Row y then takes the row `half` on, not yet changed as rows go up (beyond the last: none).
  for (int y = 0; y < rows; ++y) {
    std::uint8_t* target = row_of(y);
    if (y + half < rows) {
      const std::uint8_t* next = row_of(y + half);
      for (int x = 0; x < width; ++x) target[x] = std::max(target[x], next[x]);
    } else {
      for (int x = 0; x < width; ++x) target[x] = std::max(target[x], outside_);
    }
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
  *this = PrecomputationGridStack(std::move(cells), max_depth);
}

PrecomputationGridStack::PrecomputationGridStack(PrecomputationGrid cells, int max_depth) {
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
