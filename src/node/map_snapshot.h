// A copy of the finest map level, taken under the SLAM lock so that rasterising, drawing and
// publishing run outside it. Copying one GridMap is a few vector copies (12 bytes a cell: about
// 12 MB and a few ms for a 1024² map), far cheaper than rasterising under the lock.
#ifndef HEX_SLAM_NODE_MAP_SNAPSHOT_H_
#define HEX_SLAM_NODE_MAP_SNAPSHOT_H_

#include <cstdint>
#include <optional>

#include "hex_slam/grid_map.h"
#include "hex_slam/hex_lattice.h"
#include "hex_slam/io/occupancy_raster.h"
#include "hex_slam/slam.h"
#include "hex_slam/square_lattice.h"

namespace hex_slam {
namespace node {

struct MapSnapshot {
  std::optional<GridMap<HexLattice>> hex;  // exactly one is set, by the map's lattice
  std::optional<GridMap<SquareLattice>> square;
  std::uint64_t generation = 0;  // the map version it copies
};

// Call under the lock that guards `slam`.
MapSnapshot TakeSnapshot(const Slam& slam, std::uint64_t generation);

// The map on the square raster of equal cell area (hector's 0 free / 100 occupied / -1 unknown),
// covering the observed cells. An empty map gives one unknown pixel at the origin: consumers
// such as rviz reject zero-sized grids.
io::OccupancyRaster RasterizeSnapshot(const MapSnapshot& snapshot);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_MAP_SNAPSHOT_H_
