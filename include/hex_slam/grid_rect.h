// A rectangle of storage indices: the extent of a dense, row-major cell array.
#ifndef HEX_SLAM_GRID_RECT_H_
#define HEX_SLAM_GRID_RECT_H_

#include <algorithm>
#include <cstddef>

#include "hex_slam/grid_index.h"

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
  GridRect Union(const GridRect& r) const {
    if (empty()) return r;
    const GridIndex hi = max(), rhi = r.max();
    return FromCorners({std::min(min.col, r.min.col), std::min(min.row, r.min.row)},
                       {std::max(hi.col, rhi.col), std::max(hi.row, rhi.row)});
  }
};

}  // namespace hex_slam

#endif  // HEX_SLAM_GRID_RECT_H_
