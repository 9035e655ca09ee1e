#include "hex_slam/grid_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hex_slam/hex_lattice.h"
#include "hex_slam/square_lattice.h"
#include "ray_walk.h"

namespace hex_slam {

template <class Lattice>
GridMap<Lattice>::GridMap(const Lattice& lattice, const OccupancyModel& model,
                          const GridGrowthPolicy& growth,
                          const Eigen::AlignedBox2d& initial_extent)
    : lattice_(lattice), model_(model), growth_(growth) {
  GridIndex lo, hi;
  lattice_.IndexBounds(initial_extent, &lo, &hi);
  const GridRect rect = GridRect::FromCorners(lo, hi);
  if (static_cast<std::int64_t>(rect.size()) > growth_.max_cells) {
    throw std::invalid_argument("GridMap: initial map exceeds the cell cap");
  }
  Resize(rect);
}

template <class Lattice>
void GridMap<Lattice>::Resize(const GridRect& rect) {
  std::vector<float> log_odds(rect.size(), 0.0f);
  std::vector<float> probability(rect.size(), kUnknownProbability);
  std::vector<std::uint32_t> stamp(rect.size(), 0);
  std::vector<CellHits> hits(rect.size());
  if (!rect_.empty()) {
    for (int row = rect_.min.row; row < rect_.min.row + rect_.height; ++row) {
      const std::size_t from = rect_.Offset({rect_.min.col, row});
      const std::size_t to = rect.Offset({rect_.min.col, row});
      std::copy_n(log_odds_.begin() + from, rect_.width, log_odds.begin() + to);
      std::copy_n(probability_.begin() + from, rect_.width, probability.begin() + to);
      std::copy_n(stamp_.begin() + from, rect_.width, stamp.begin() + to);
      std::copy_n(hits_.begin() + from, rect_.width, hits.begin() + to);
    }
  }
  rect_ = rect;
  log_odds_.swap(log_odds);
  probability_.swap(probability);
  stamp_.swap(stamp);
  hits_.swap(hits);
}

template <class Lattice>
bool GridMap<Lattice>::EnsureCovers(const Eigen::AlignedBox2d& box) {
  GridIndex lo, hi;
  lattice_.IndexBounds(box, &lo, &hi);
  const GridRect needed = GridRect::FromCorners(lo, hi);
  if (needed.empty()) return false;  // a NaN box: its cells are clamped far apart, inverted
  if (rect_.Contains(needed)) return true;
  if (!growth_.auto_grow) return false;

  // Grow each violated side by at least a fraction of the current size, plus a margin.
  const int grow_w = std::max(1, static_cast<int>(rect_.width * growth_.min_growth_fraction));
  const int grow_h = std::max(1, static_cast<int>(rect_.height * growth_.min_growth_fraction));
  GridIndex new_lo = rect_.min, new_hi = rect_.max();
  const int m = growth_.margin_cells;
  if (lo.col < new_lo.col) new_lo.col = std::min(lo.col - m, new_lo.col - grow_w);
  if (lo.row < new_lo.row) new_lo.row = std::min(lo.row - m, new_lo.row - grow_h);
  if (hi.col > new_hi.col) new_hi.col = std::max(hi.col + m, new_hi.col + grow_w);
  if (hi.row > new_hi.row) new_hi.row = std::max(hi.row + m, new_hi.row + grow_h);
  GridRect grown = GridRect::FromCorners(new_lo, new_hi);
  if (static_cast<std::int64_t>(grown.size()) > growth_.max_cells) {
    grown = rect_.Union(needed);  // the least growth that still covers the scan
    if (static_cast<std::int64_t>(grown.size()) > growth_.max_cells) return false;
  }
  Resize(grown);
  ++growth_count_;
  return true;
}

template <class Lattice>
void GridMap<Lattice>::NextStamps() {
  if (occupied_stamp_ >= std::numeric_limits<std::uint32_t>::max() - 2) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    occupied_stamp_ = 1;
  }
  free_stamp_ = occupied_stamp_ + 1;
  occupied_stamp_ = free_stamp_ + 1;
}

template <class Lattice>
void GridMap<Lattice>::SetLogOdds(std::size_t offset, float value) {
  value = std::min(model_.max_log_odds, std::max(model_.min_log_odds, value));
  log_odds_[offset] = value;
  probability_[offset] = OccupancyModel::Probability(value);
  CellHits& h = hits_[offset];
  if (h.count > 0.0f) Reweigh(&h, probability_[offset]);
}

template <class Lattice>
void GridMap<Lattice>::Reweigh(CellHits* h, float probability) {
  const float weight = std::max(probability, kMinCellHitWeight);
  const float scale = weight / h->weight;
  h->weight = weight;
  h->x *= scale;
  h->y *= scale;
}

template <class Lattice>
void GridMap<Lattice>::MarkFree(std::size_t offset) {
  if (stamp_[offset] >= free_stamp_) return;  // already freed or hit by this scan
  stamp_[offset] = free_stamp_;
  SetLogOdds(offset, log_odds_[offset] + model_.free_delta);
}

template <class Lattice>
void GridMap<Lattice>::MarkOccupied(std::size_t offset) {
  if (stamp_[offset] >= occupied_stamp_) return;
  float value = log_odds_[offset];
  if (stamp_[offset] == free_stamp_) value -= model_.free_delta;  // an earlier beam freed it
  stamp_[offset] = occupied_stamp_;
  SetLogOdds(offset, value + model_.occupied_delta);
}

template <class Lattice>
void GridMap<Lattice>::AddHit(std::size_t offset, const Eigen::Vector2d& relative) {
  CellHits& h = hits_[offset];
  const Eigen::Vector2f mean = h.Mean();
  const float count = std::min(h.count + 1.0f, kHitMemory);
  SetHits(offset, mean + (relative.cast<float>() - mean) / count, count);
}

template <class Lattice>
void GridMap<Lattice>::InsertScan(const Eigen::Vector2d& origin,
                                  const std::vector<Eigen::Vector2d>& endpoints) {
  Eigen::AlignedBox2d box(origin);
  for (const Eigen::Vector2d& p : endpoints) box.extend(p);
  EnsureCovers(box);
  NextStamps();
  const Cell start = lattice_.CellOf(origin);
  const auto mark_free = [this](const Cell& cell) {
    const GridIndex index = Lattice::ToIndex(cell);
    if (rect_.Contains(index)) MarkFree(rect_.Offset(index));
  };
  for (const Eigen::Vector2d& p : endpoints) {
    const Cell end_cell = lattice_.CellOf(p);
    const GridIndex end = Lattice::ToIndex(end_cell);
    // Beyond the growth cap, or not a finite point (which the box above does not see).
    if (!rect_.Contains(end)) {
      ++points_outside_;
      continue;
    }
    WalkRay(lattice_, origin, start, p, end_cell, mark_free);
    const std::size_t offset = rect_.Offset(end);
    MarkOccupied(offset);
    AddHit(offset, p - lattice_.CentreOf(Lattice::FromIndex(end)));
  }
}

template <class Lattice>
void GridMap<Lattice>::Clear() {
  std::fill(log_odds_.begin(), log_odds_.end(), 0.0f);
  std::fill(probability_.begin(), probability_.end(), kUnknownProbability);
  std::fill(stamp_.begin(), stamp_.end(), 0);
  std::fill(hits_.begin(), hits_.end(), CellHits());
  points_outside_ = 0;
}

template <class Lattice>
void GridMap<Lattice>::Assign(const GridRect& rect, std::vector<float> log_odds) {
  if (log_odds.size() != rect.size()) {
    throw std::invalid_argument("GridMap::Assign: cell count does not match the rectangle");
  }
  rect_ = rect;
  log_odds_ = std::move(log_odds);
  probability_.resize(rect.size());
  stamp_.assign(rect.size(), 0);
  hits_.assign(rect.size(), CellHits());
  for (std::size_t i = 0; i < log_odds_.size(); ++i) SetLogOdds(i, log_odds_[i]);
}

template <class Lattice>
void GridMap<Lattice>::SetHits(std::size_t offset, const Eigen::Vector2f& mean, float count) {
  CellHits& h = hits_[offset];
  h.count = count;
  h.weight = std::max(probability_[offset], kMinCellHitWeight);
  h.x = h.weight * mean.x();
  h.y = h.weight * mean.y();
}

template <class Lattice>
Eigen::AlignedBox2d GridMap<Lattice>::StorageExtent() const {
  Eigen::AlignedBox2d box;
  const GridIndex hi = rect_.max();
  for (const GridIndex& corner :
       {rect_.min, hi, GridIndex{rect_.min.col, hi.row}, GridIndex{hi.col, rect_.min.row}}) {
    box.extend(lattice_.CentreOf(Lattice::FromIndex(corner)));
  }
  return box;
}

template <class Lattice>
Eigen::AlignedBox2d GridMap<Lattice>::KnownExtent() const {
  Eigen::AlignedBox2d box;
  for (std::size_t i = 0; i < log_odds_.size(); ++i) {
    if (log_odds_[i] != 0.0f) box.extend(lattice_.CentreOf(Lattice::FromIndex(rect_.IndexAt(i))));
  }
  return box;
}

template <class Lattice>
std::size_t GridMap<Lattice>::MemoryBytes() const {
  return log_odds_.capacity() * sizeof(float) + probability_.capacity() * sizeof(float) +
         stamp_.capacity() * sizeof(std::uint32_t) + hits_.capacity() * sizeof(CellHits);
}

template class GridMap<HexLattice>;
template class GridMap<SquareLattice>;

}  // namespace hex_slam
