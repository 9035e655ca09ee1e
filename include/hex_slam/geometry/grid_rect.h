// A rectangle of storage indices: the extent of a dense, row-major cell array.
#ifndef HEX_SLAM_GEOMETRY_GRID_RECT_H_
#define HEX_SLAM_GEOMETRY_GRID_RECT_H_

#include <algorithm>
#include <cstddef>

#include "hex_slam/geometry/grid_index.h"

namespace hex_slam {

struct GridRect {
  GridIndex min;  // first column and row
  int width = 0;
  int height = 0;

  static GridRect FromCorners(const GridIndex& lo, const GridIndex& hi) {
    return {lo, hi.col - lo.col + 1, hi.row - lo.row + 1};
  }
  GridIndex max() const { return {min.col + width - 1, min.row + height - 1}; }
  std::size_t size() const { return static_cast<std::size_t>(width) * height; }
  bool empty() const { return width <= 0 || height <= 0; }

  bool Contains(const GridIndex& i) const {
    return static_cast<unsigned>(i.col - min.col) < static_cast<unsigned>(width) &&
           static_cast<unsigned>(i.row - min.row) < static_cast<unsigned>(height);
  }
  bool Contains(const GridRect& r) const { return Contains(r.min) && Contains(r.max()); }
  // Row-major offset; only meaningful when Contains(i).
  std::size_t Offset(const GridIndex& i) const {
    return static_cast<std::size_t>(i.row - min.row) * width + (i.col - min.col);
  }
  GridIndex IndexAt(std::size_t offset) const {
    return {min.col + static_cast<int>(offset % width), min.row + static_cast<int>(offset / width)};
  }
  // The cells in both; empty when they do not overlap.
  GridRect Intersect(const GridRect& r) const {
    if (empty() || r.empty()) return GridRect();
    const GridIndex hi = max(), rhi = r.max();
    const GridIndex lo{std::max(min.col, r.min.col), std::max(min.row, r.min.row)};
    const GridIndex top{std::min(hi.col, rhi.col), std::min(hi.row, rhi.row)};
    if (top.col < lo.col || top.row < lo.row) return GridRect();
    return FromCorners(lo, top);
  }
  // `margin` more cells on every side.
  GridRect Grown(int margin) const {
    if (empty()) return *this;
    return {{min.col - margin, min.row - margin}, width + 2 * margin, height + 2 * margin};
  }
  GridRect Union(const GridRect& r) const {
    if (empty()) return r;
    if (r.empty()) return *this;
    const GridIndex hi = max(), rhi = r.max();
    return FromCorners({std::min(min.col, r.min.col), std::min(min.row, r.min.row)},
                       {std::max(hi.col, rhi.col), std::max(hi.row, rhi.row)});
  }
};

// Copies the cells of `region` (inside both rectangles) between two row-major arrays laid out
// over `from_rect` and `to_rect`, a row at a time.
template <class T>
void CopyRegion(const T* from, const GridRect& from_rect, T* to, const GridRect& to_rect,
                const GridRect& region) {
  for (int row = region.min.row; row < region.min.row + region.height; ++row) {
    const GridIndex first{region.min.col, row};
    std::copy_n(from + from_rect.Offset(first), region.width, to + to_rect.Offset(first));
  }
}

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_GRID_RECT_H_
