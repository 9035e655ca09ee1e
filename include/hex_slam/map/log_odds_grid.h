// The log-odds of a grid's cells on any lattice, and nothing else: what a map reads as
// occupied, free or unknown. GridMap keeps one as its primary record; the node's map thread keeps
// a copy to rasterise, draw and plan on, refreshed region by region so that no reader ever
// copies a whole map.
#ifndef HEX_SLAM_MAP_LOG_ODDS_GRID_H_
#define HEX_SLAM_MAP_LOG_ODDS_GRID_H_

#include <algorithm>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/geometry/grid_rect.h"
#include "hex_slam/map/occupancy_model.h"
#include "hex_slam/map/zeroed_array.h"

namespace hex_slam {

template <class Lattice>
class LogOddsGrid {
 public:
  using Cell = typename Lattice::Cell;

  explicit LogOddsGrid(const Lattice& lattice) : lattice_(lattice) {}

  const Lattice& lattice() const { return lattice_; }
  // The storage rectangle.
  const GridRect& rect() const { return rect_; }
  // The smallest rectangle holding every cell written since the last Clear(): every cell outside
  // it is unknown, and only its pages of storage hold memory.
  const GridRect& written() const { return written_; }

  float LogOddsAt(const GridIndex& index) const {
    return rect_.Contains(index) ? values_[rect_.Offset(index)] : 0.0f;
  }
  float LogOdds(const Cell& cell) const { return LogOddsAt(Lattice::ToIndex(cell)); }
  bool IsKnownAt(const GridIndex& index) const { return LogOddsAt(index) != 0.0f; }
  float ProbabilityAt(const GridIndex& index) const {
    return OccupancyModel::Probability(LogOddsAt(index));
  }
  // Row-major over rect().
  const float* data() const { return values_.data(); }
  // Sized then copied: GCC 12 inlines the range constructor over this storage into a false
  // -Wfree-nonheap-object warning.
  std::vector<float> values() const {
    std::vector<float> copy(values_.size());
    std::copy(values_.begin(), values_.end(), copy.begin());
    return copy;
  }
  float* mutable_data() { return values_.data(); }

  // The world box of the storage's corner cells' centres.
  Eigen::AlignedBox2d StorageExtent() const {
    Eigen::AlignedBox2d box;
    const GridIndex hi = rect_.max();
    for (const GridIndex& corner :
         {rect_.min, hi, GridIndex{rect_.min.col, hi.row}, GridIndex{hi.col, rect_.min.row}}) {
      box.extend(lattice_.CentreOf(corner));
    }
    return box;
  }

  // The world box of the cells observed at least once (empty if none).
  Eigen::AlignedBox2d KnownExtent() const {
    Eigen::AlignedBox2d box;
    ForEachKnown([&](std::size_t, const GridIndex& index, float) {
      box.extend(lattice_.CentreOf(index));
    });
    return box;
  }

  // Calls visit(offset, index) for every cell of written(), row by row.
  template <class Visit>
  void ForEachWritten(Visit&& visit) const {
    for (int row = written_.min.row; row < written_.min.row + written_.height; ++row) {
      for (int col = written_.min.col; col < written_.min.col + written_.width; ++col) {
        const GridIndex index{col, row};
        visit(rect_.Offset(index), index);
      }
    }
  }
  // Calls visit(offset, index, log_odds) for every observed cell, row by row.
  template <class Visit>
  void ForEachKnown(Visit&& visit) const {
    ForEachWritten([&](std::size_t offset, const GridIndex& index) {
      if (values_[offset] != 0.0f) visit(offset, index, values_[offset]);
    });
  }

  // New storage over `rect`, keeping the values that lie inside it.
  void Reshape(const GridRect& rect, Paging paging = Paging::kOnFirstWrite) {
    ZeroedArray<float> values(rect.size(), paging);
    const GridRect kept = written_.Intersect(rect);
    if (!kept.empty()) CopyRegion(values_.data(), rect_, values.data(), rect, kept);
    values_.swap(values);
    rect_ = rect;
    written_ = kept;
  }
  // Every cell unknown again; the storage keeps its rectangle but gives its pages back.
  void Clear() {
    values_.Reset(rect_.size());
    written_ = GridRect();
  }
  // Records that cells of `region` may have been written.
  void MarkWritten(const GridRect& region) { written_ = written_.Union(region.Intersect(rect_)); }

  // Brings `region` of this copy up to `source` (the same lattice). A source whose storage has
  // another rectangle (it grew, or was replaced) is copied whole; so is everything when `region`
  // is empty and `all` is set.
  void CopyFrom(const LogOddsGrid& source, const GridRect& region, bool all = false) {
    if (all || !(rect_.min == source.rect_.min && rect_.width == source.rect_.width &&
                 rect_.height == source.rect_.height)) {
      rect_ = source.rect_;
      values_.Reset(rect_.size());
      written_ = GridRect();
      CopyWritten(source, source.written_);
      return;
    }
    CopyWritten(source, region.Intersect(rect_));
  }

 private:
  void CopyWritten(const LogOddsGrid& source, const GridRect& region) {
    if (region.empty()) return;
    CopyRegion(source.values_.data(), source.rect_, values_.data(), rect_, region);
    written_ = written_.Union(region);
  }

  Lattice lattice_;
  GridRect rect_;
  GridRect written_;
  ZeroedArray<float> values_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_LOG_ODDS_GRID_H_
