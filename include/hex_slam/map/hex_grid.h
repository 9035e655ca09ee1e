// The hexagonal occupancy grid: GridMap on the HexLattice (instantiated in grid_map.cpp).
#ifndef HEX_SLAM_MAP_HEX_GRID_H_
#define HEX_SLAM_MAP_HEX_GRID_H_

#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/hex_lattice.h"

namespace hex_slam {

extern template class GridMap<HexLattice>;
using HexGrid = GridMap<HexLattice>;

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_HEX_GRID_H_
