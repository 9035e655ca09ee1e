#include "hex_slam/map/grid_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"
#include "geometry/ray_walk.h"

namespace hex_slam {
namespace {

// Cells of slack around a scan's bounding box when recording what it wrote: a ray's cells reach
// up to a cell past the box of its end points.
constexpr int kWrittenMargin = 2;

// New zeroed storage over `to` holding `from`'s values in `kept`.
template <class T>
void Move(ZeroedArray<T>* array, const GridRect& from, const GridRect& to, const GridRect& kept,
          Paging paging) {
  ZeroedArray<T> moved(to.size(), paging);
  if (!kept.empty()) CopyRegion(array->data(), from, moved.data(), to, kept);
  array->swap(moved);
}

}  // namespace

template <class Lattice>
GridMap<Lattice>::GridMap(const Lattice& lattice, const OccupancyModel& model,
                          const GridGrowthPolicy& growth,
                          const Eigen::AlignedBox2d& initial_extent)
    : model_(model), growth_(growth), log_odds_(lattice) {
  GridIndex lo, hi;
  lattice.IndexBounds(initial_extent, &lo, &hi);
  const GridRect rect = GridRect::FromCorners(lo, hi);
  if (static_cast<std::int64_t>(rect.size()) > growth_.max_cells) {
    throw std::invalid_argument("GridMap: initial map exceeds the cell cap");
  }
  ResetHitRecords();
  Resize(rect);
}

template <class Lattice>
void GridMap<Lattice>::ResetHitRecords() {
  hit_records_.assign(1, CellHits());
}

template <class Lattice>
void GridMap<Lattice>::Resize(const GridRect& rect) {
  // Only the written cells move: the rest is zero in both, and copying it would make its pages
  // resident.
  const GridRect old_rect = log_odds_.rect();
  const GridRect kept = log_odds_.written().Intersect(rect);
  const bool stamps = stamps_held();
  Move(&centred_, old_rect, rect, kept, paging());
  Move(&hit_slot_, old_rect, rect, kept, paging());
  if (stamps) Move(&stamp_, old_rect, rect, kept, paging());
  log_odds_.Reshape(rect, paging());
}

template <class Lattice>
bool GridMap<Lattice>::EnsureCovers(const Eigen::AlignedBox2d& box) {
  GridIndex lo, hi;
  lattice().IndexBounds(box, &lo, &hi);
  const GridRect needed = GridRect::FromCorners(lo, hi);
  if (needed.empty()) return false;  // a NaN box: its cells are clamped far apart, inverted
  const GridRect& current = rect();
  if (current.Contains(needed)) return true;
  if (!growth_.auto_grow) return false;

  // Grow each violated side by at least a fraction of the current size, plus a margin.
  const int grow_w = std::max(1, static_cast<int>(current.width * growth_.min_growth_fraction));
  const int grow_h = std::max(1, static_cast<int>(current.height * growth_.min_growth_fraction));
  GridIndex new_lo = current.min, new_hi = current.max();
  const int m = growth_.margin_cells;
  if (lo.col < new_lo.col) new_lo.col = std::min(lo.col - m, new_lo.col - grow_w);
  if (lo.row < new_lo.row) new_lo.row = std::min(lo.row - m, new_lo.row - grow_h);
  if (hi.col > new_hi.col) new_hi.col = std::max(hi.col + m, new_hi.col + grow_w);
  if (hi.row > new_hi.row) new_hi.row = std::max(hi.row + m, new_hi.row + grow_h);
  GridRect grown = GridRect::FromCorners(new_lo, new_hi);
  if (static_cast<std::int64_t>(grown.size()) > growth_.max_cells) {
    grown = current.Union(needed);  // the least growth that still covers the scan
    if (static_cast<std::int64_t>(grown.size()) > growth_.max_cells) return false;
  }
  Resize(grown);
  ++growth_count_;
  return true;
}

template <class Lattice>
bool GridMap<Lattice>::Reserve(const Eigen::AlignedBox2d& box) {
  GridIndex lo, hi;
  lattice().IndexBounds(box, &lo, &hi);
  const GridRect needed = GridRect::FromCorners(lo, hi);
  if (needed.empty()) return false;
  if (rect().Contains(needed)) return true;
  const GridRect reserved = rect().Union(needed);
  if (static_cast<std::int64_t>(reserved.size()) > growth_.max_cells) return false;
  Resize(reserved);
  return true;
}

template <class Lattice>
void GridMap<Lattice>::ShrinkToWritten() {
  const GridRect kept = log_odds_.written().Intersect(rect());
  if (kept.size() < rect().size()) Resize(kept);
  // The stamps only keep one scan from updating a cell twice: a map that takes no more scans
  // has no use for them (a seventh of a cell's bytes), and the hit records no room to grow.
  stamp_ = ZeroedArray<std::uint16_t>();
  hit_records_.shrink_to_fit();
}

template <class Lattice>
void GridMap<Lattice>::RestoreStamps() {
  stamp_ = ZeroedArray<std::uint16_t>(rect().size(), paging());
  free_stamp_ = 0;
  occupied_stamp_ = 1;
}

template <class Lattice>
void GridMap<Lattice>::NextStamps() {
  if (occupied_stamp_ >= std::numeric_limits<std::uint16_t>::max() - 2) {
    // Stamps are non-zero only where cells were written.
    const GridRect& written = log_odds_.written();
    for (int row = written.min.row; row < written.min.row + written.height; ++row) {
      std::fill_n(stamp_.data() + rect().Offset({written.min.col, row}), written.width, 0);
    }
    occupied_stamp_ = 1;
  }
  free_stamp_ = occupied_stamp_ + 1;
  occupied_stamp_ = free_stamp_ + 1;
}

template <class Lattice>
void GridMap<Lattice>::SetLogOdds(std::size_t offset, float value) {
  value = std::min(model_.max_log_odds, std::max(model_.min_log_odds, value));
  float& stored = log_odds_.mutable_data()[offset];
  // A cell at its clamp pushed further (free space, after a few scans) keeps its value, and so
  // its probability and its hits' weight, which are that value's already: no exp to redo.
  if (value == stored) return;
  stored = value;
  centred_[offset] = OccupancyModel::Probability(value) - kUnknownProbability;
  const std::uint32_t slot = hit_slot_[offset];
  // The weight is the probability as the matchers read it, so a saved and reloaded map gets
  // exactly the same weights.
  if (slot != 0) Reweigh(&hit_records_[slot], kUnknownProbability + centred_[offset]);
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
  SetLogOdds(offset, log_odds_.data()[offset] + model_.free_delta);
}

template <class Lattice>
void GridMap<Lattice>::MarkOccupied(std::size_t offset) {
  if (stamp_[offset] >= occupied_stamp_) return;
  float value = log_odds_.data()[offset];
  if (stamp_[offset] == free_stamp_) value -= model_.free_delta;  // an earlier beam freed it
  stamp_[offset] = occupied_stamp_;
  SetLogOdds(offset, value + model_.occupied_delta);
}

template <class Lattice>
void GridMap<Lattice>::AddHit(std::size_t offset, const Eigen::Vector2d& relative) {
  const CellHits& h = HitsAt(offset);
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
  GridIndex lo, hi;
  lattice().IndexBounds(box, &lo, &hi);
  log_odds_.MarkWritten(GridRect::FromCorners(lo, hi).Grown(kWrittenMargin));
  if (!stamps_held()) RestoreStamps();
  NextStamps();
  const Lattice& lattice = this->lattice();
  const GridRect& rect = this->rect();
  const Cell start = lattice.CellOf(origin);
  const auto mark_free = [this, &rect](const Cell& cell) {
    const GridIndex index = Lattice::ToIndex(cell);
    if (rect.Contains(index)) MarkFree(rect.Offset(index));
  };
  for (const Eigen::Vector2d& p : endpoints) {
    const Cell end_cell = lattice.CellOf(p);
    const GridIndex end = Lattice::ToIndex(end_cell);
    // Beyond the growth cap, or not a finite point (which the box above does not see).
    if (!rect.Contains(end)) {
      ++points_outside_;
      continue;
    }
    WalkRay(lattice, origin, start, p, end_cell, mark_free);
    const std::size_t offset = rect.Offset(end);
    MarkOccupied(offset);
    AddHit(offset, p - lattice.CentreOf(Lattice::FromIndex(end)));
  }
}

template <class Lattice>
void GridMap<Lattice>::Clear() {
  const std::size_t size = rect().size();
  log_odds_.Clear();
  centred_.Reset(size);
  hit_slot_.Reset(size);
  ResetHitRecords();
  RestoreStamps();
  points_outside_ = 0;
}

template <class Lattice>
void GridMap<Lattice>::Assign(const GridRect& rect, const std::vector<float>& log_odds) {
  if (log_odds.size() != rect.size()) {
    throw std::invalid_argument("GridMap::Assign: cell count does not match the rectangle");
  }
  log_odds_.Reshape(rect, paging());
  log_odds_.Clear();
  Clear();
  for (std::size_t i = 0; i < log_odds.size(); ++i) {
    if (log_odds[i] == 0.0f) continue;
    SetLogOdds(i, log_odds[i]);
    const GridIndex index = rect.IndexAt(i);
    log_odds_.MarkWritten({index, 1, 1});
  }
}

template <class Lattice>
void GridMap<Lattice>::SetHits(std::size_t offset, const Eigen::Vector2f& mean, float count) {
  std::uint32_t& slot = hit_slot_[offset];
  if (slot == 0) {
    if (hit_records_.size() > std::numeric_limits<std::uint32_t>::max()) {
      throw std::length_error("GridMap: more hit cells than 32-bit slots");
    }
    slot = static_cast<std::uint32_t>(hit_records_.size());
    hit_records_.emplace_back();
    // A restored hit may sit on a cell of log-odds 0 outside the written region; it must still
    // be visited (CaptureHexMap), or a saved map would not come back cell for cell.
    log_odds_.MarkWritten({log_odds_.rect().IndexAt(offset), 1, 1});
  }
  CellHits& h = hit_records_[slot];
  h.count = count;
  h.weight = std::max(kUnknownProbability + centred_[offset], kMinCellHitWeight);
  h.x = h.weight * mean.x();
  h.y = h.weight * mean.y();
}

template <class Lattice>
std::size_t GridMap<Lattice>::MemoryBytes() const {
  const GridRect& held = growth_.prefault ? rect() : log_odds_.written();
  const std::size_t per_cell = kBytesPerCell - (stamps_held() ? 0 : sizeof(std::uint16_t));
  return held.size() * per_cell + hit_records_.capacity() * sizeof(CellHits);
}

template class GridMap<HexLattice>;
template class GridMap<SquareLattice>;

}  // namespace hex_slam
