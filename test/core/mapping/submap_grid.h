// The submap grids the mapping tests build: 5 cm cells and hector's occupancy factors.
#ifndef HEX_SLAM_TEST_CORE_MAPPING_SUBMAP_GRID_H_
#define HEX_SLAM_TEST_CORE_MAPPING_SUBMAP_GRID_H_

#include "hex_slam/mapping/submap.h"

namespace hex_slam {
namespace testing_util {

inline mapping::SubmapGridParameters SubmapGrid(int levels) {
  mapping::SubmapGridParameters grid;
  grid.finest_spacing = 0.05;
  grid.levels = levels;
  grid.model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  return grid;
}

}  // namespace testing_util
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_CORE_MAPPING_SUBMAP_GRID_H_
