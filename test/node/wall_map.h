// Test maps for the node's tests: a straight wall seen from the origin, so cells before it are
// free and cells on it occupied.
#ifndef HEX_SLAM_TEST_NODE_WALL_MAP_H_
#define HEX_SLAM_TEST_NODE_WALL_MAP_H_

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/map/occupancy_model.h"

namespace hex_slam {
namespace testing_util {

// The wall x = `x`, |y| <= `half_length`, one endpoint every 2 cm. `Map`: a GridMap or a
// MapPyramid.
template <class Map>
void InsertWall(double x, double half_length, Map* map) {
  std::vector<Eigen::Vector2d> wall;
  for (double y = -half_length; y <= half_length; y += 0.02) wall.emplace_back(x, y);
  map->InsertScan({0.0, 0.0}, wall);
}

inline OccupancyModel HectorModel() { return OccupancyModel::FromFactors(0.4, 0.9, 50.0); }

inline Eigen::AlignedBox2d Square(double half_side) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(-half_side, -half_side),
                             Eigen::Vector2d(half_side, half_side));
}

}  // namespace testing_util
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_NODE_WALL_MAP_H_
