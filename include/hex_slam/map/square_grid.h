// The square occupancy grid of the hector_mapping baseline (instantiated in grid_map.cpp).
#ifndef HEX_SLAM_MAP_SQUARE_GRID_H_
#define HEX_SLAM_MAP_SQUARE_GRID_H_

#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {

extern template class GridMap<SquareLattice>;
using SquareGrid = GridMap<SquareLattice>;

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_SQUARE_GRID_H_
