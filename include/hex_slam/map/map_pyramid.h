// A stack of occupancy grids on one lattice, level k with spacing d·2^k (4^k times the cell
// area), all updated with every inserted scan; matching runs coarse to fine over it.
#ifndef HEX_SLAM_MAP_MAP_PYRAMID_H_
#define HEX_SLAM_MAP_MAP_PYRAMID_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/map/grid_map.h"

namespace hex_slam {

template <class Lattice>
class MapPyramid {
 public:
  MapPyramid(double finest_spacing, int levels, const OccupancyModel& model,
             const GridGrowthPolicy& growth, const Eigen::AlignedBox2d& initial_extent) {
    double spacing = finest_spacing;
    for (int k = 0; k < levels; ++k, spacing *= 2.0) {
      levels_.emplace_back(Lattice(spacing), model, growth, initial_extent);
    }
  }

  int size() const { return static_cast<int>(levels_.size()); }
  // Level 0 is the finest.
  const GridMap<Lattice>& level(int k) const { return levels_[k]; }
  GridMap<Lattice>& mutable_level(int k) { return levels_[k]; }

  void InsertScan(const Eigen::Vector2d& origin, const std::vector<Eigen::Vector2d>& endpoints) {
    for (auto& grid : levels_) grid.InsertScan(origin, endpoints);
  }
  void Clear() {
    for (auto& grid : levels_) grid.Clear();
  }
  // Grows every level's storage to cover `box` (as the growth policy allows).
  void EnsureCovers(const Eigen::AlignedBox2d& box) {
    for (auto& grid : levels_) grid.EnsureCovers(box);
  }
  void ShrinkToWritten() {
    for (auto& grid : levels_) grid.ShrinkToWritten();
  }
  // Every level's storage over `box` as well, exactly (GridMap::Reserve).
  void Reserve(const Eigen::AlignedBox2d& box) {
    for (auto& grid : levels_) grid.Reserve(box);
  }
  std::size_t MemoryBytes() const {
    std::size_t bytes = 0;
    for (const auto& grid : levels_) bytes += grid.MemoryBytes();
    return bytes;
  }

 private:
  std::vector<GridMap<Lattice>> levels_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_MAP_PYRAMID_H_
