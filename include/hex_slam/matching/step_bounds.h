// Upper bounds of a lattice map's occupancy probabilities on a square grid whose pixels are a
// search's translation step wide: the correlative search's branch and bound. A search that
// slides a scan by whole steps moves every endpoint by whole pixels, so a block of 2^k × 2^k
// shifts reads, per endpoint, one value of the grid max-pooled over 2^k × 2^k pixels; summed,
// an upper bound of every score in the block. The pixels need not line up with the cells (hex
// or square): each pixel holds the largest probability of any cell that can meet it.
#ifndef HEX_SLAM_MATCHING_STEP_BOUNDS_H_
#define HEX_SLAM_MATCHING_STEP_BOUNDS_H_

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/matching/precomputation_grid.h"

namespace hex_slam {
namespace matching {

// Along one axis: the index of the pixel (pixels `pixel` m wide, the first with its corner at the
// world origin) holding coordinate `v`; beyond a billion pixels (no map reaches it) the last one.
inline int PixelIndexOf(double v, double pixel) {
  static constexpr double kFarthest = 1e9;
  return static_cast<int>(std::clamp(std::floor(v / pixel), -kFarthest, kFarthest));
}

// The pixel holding `point`.
inline Eigen::Array2i PixelOf(const Eigen::Vector2d& point, double pixel) {
  return {PixelIndexOf(point.x(), pixel), PixelIndexOf(point.y(), pixel)};
}

// Depth 0: every pixel that meets `reach` (a world box) holds at least the largest probability
// of any cell that meets it (rounded up to the grid's codes), and a point a hair outside the
// pixel (the rounding of a shifted coordinate) is still bounded by it. Only the pixels a written
// cell can meet are stored; every other reads as GridMap::kUnknownProbability, which beyond
// `reach` need not bound the map: a search reads only within it.
template <class Lattice>
PrecomputationGrid PixelBounds(const GridMap<Lattice>& grid, double pixel,
                               const Eigen::AlignedBox2d& reach);

// The world box whose pixels PixelBounds stores: where a written cell can meet `reach` (empty
// when none can).
template <class Lattice>
Eigen::AlignedBox2d BoundedBox(const GridMap<Lattice>& grid, const Eigen::AlignedBox2d& reach);

}  // namespace matching
}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_STEP_BOUNDS_H_
