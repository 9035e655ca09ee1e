// The map drawn as its actual cells: one polygon per observed cell (hexagons on the hex lattice,
// squares on the square one), grey by occupancy (white free, black occupied), as a
// visualization_msgs/Marker TRIANGLE_LIST rviz draws directly. Unknown cells are not drawn, so
// the message grows with the explored area, not with the map's storage.
#ifndef HEX_SLAM_NODE_MAP_OUTPUT_HEX_MAP_MARKER_H_
#define HEX_SLAM_NODE_MAP_OUTPUT_HEX_MAP_MARKER_H_

#include <string>

#include <ros/time.h>
#include <visualization_msgs/Marker.h>

#include "map_output/map_snapshot.h"

namespace hex_slam {
namespace node {

struct MarkerStyle {
  // Each cell is drawn shrunk about its centre so the lattice shows between neighbours.
  double cell_scale = 0.9;
  // Just above the occupancy grid at z = 0, so both can be shown together.
  double height = 0.01;  // m
  int max_cells = 200000;
};

struct MarkerStats {
  int known_cells = 0;
  int drawn_cells = 0;  // less than known_cells when max_cells cut the drawing short
};

// The cells of `grid` (one level of the map, e.g. a MapSnapshot's drawn()).
template <class Lattice>
visualization_msgs::Marker MakeHexMapMarker(const LogOddsGrid<Lattice>& grid,
                                            const MarkerStyle& style, const std::string& frame,
                                            const ros::Time& stamp, MarkerStats* stats);

// The snapshot's drawn level, whichever its lattice.
visualization_msgs::Marker MakeHexMapMarker(const MapSnapshot& snapshot, const MarkerStyle& style,
                                            const std::string& frame, const ros::Time& stamp,
                                            MarkerStats* stats);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_MAP_OUTPUT_HEX_MAP_MARKER_H_
