// The map thread's copy of the SLAM's map: the log-odds of the finest level (the /map raster,
// dynamic_map, save_map's image, the planner) and of the level the hex_map marker draws. It is
// brought up to date under the SLAM lock region by region: only the cells the scans changed since
// the last refresh are copied (a few hundred kB for a scan of a room), never the whole map, and
// rasterising, drawing and planning then run outside the lock.
#ifndef HEX_SLAM_NODE_MAP_OUTPUT_MAP_SNAPSHOT_H_
#define HEX_SLAM_NODE_MAP_OUTPUT_MAP_SNAPSHOT_H_

#include <cstdint>
#include <optional>

#include <Eigen/Geometry>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/io/occupancy_raster.h"
#include "hex_slam/map/log_odds_grid.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/mapping/slam.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace node {

// Copies of two levels of one pyramid.
template <class Lattice>
class PyramidCopy {
 public:
  // `drawn_level` is clamped to the pyramid's levels.
  PyramidCopy(const MapPyramid<Lattice>& maps, int drawn_level);

  const LogOddsGrid<Lattice>& finest() const { return finest_; }
  const LogOddsGrid<Lattice>& drawn() const { return drawn_level_ == 0 ? finest_ : drawn_; }
  int drawn_level() const { return drawn_level_; }

  // Copies the cells of `maps` inside the world box `changed`, or all of them with `all`.
  void Refresh(const MapPyramid<Lattice>& maps, const Eigen::AlignedBox2d& changed, bool all);

 private:
  int drawn_level_;
  LogOddsGrid<Lattice> finest_;
  LogOddsGrid<Lattice> drawn_;  // unused when drawn_level_ is 0
};

struct MapSnapshot {
  std::optional<PyramidCopy<HexLattice>> hex;  // exactly one is set, by the map's lattice
  std::optional<PyramidCopy<SquareLattice>> square;
  std::uint64_t generation = 0;  // the map version it copies
};

// Brings `snapshot` to `slam`'s map at version `generation`: the cells inside `changed` (the
// world box of every update since the last refresh), or everything with `all` (after a reset, a
// loaded map, or the first time). Call under the lock that guards `slam`.
void UpdateSnapshot(const Slam& slam, const Eigen::AlignedBox2d& changed, bool all,
                     std::uint64_t generation, int drawn_level, MapSnapshot* snapshot);
// The same from a pyramid held elsewhere (the node's redrawn map): exactly one is non-null.
void UpdateSnapshot(const MapPyramid<HexLattice>* hex, const MapPyramid<SquareLattice>* square,
                    const Eigen::AlignedBox2d& changed, bool all, std::uint64_t generation,
                    int drawn_level, MapSnapshot* snapshot);

// The finest level on a square raster of `resolution` m pixels (hector's 0 free / 100 occupied /
// -1 unknown), covering the observed cells. An empty map gives one unknown pixel at the origin:
// consumers such as rviz reject zero-sized grids.
io::OccupancyRaster RasterizeSnapshot(const MapSnapshot& snapshot, double resolution);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_MAP_OUTPUT_MAP_SNAPSHOT_H_
