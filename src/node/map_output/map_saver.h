// save_map's files: <base>.pgm + <base>.yaml (map_server's format, for map_server, AMCL and every
// other ROS tool) and <base>.hexmap (the native file, every level's cells exactly). The three are
// written as one set (atomic_file.h): all of them or, on any error, none, so neither a crash
// mid-save nor a bad target (a .yaml that is a directory) leaves a half-written or stray file.
#ifndef HEX_SLAM_NODE_MAP_OUTPUT_MAP_SAVER_H_
#define HEX_SLAM_NODE_MAP_OUTPUT_MAP_SAVER_H_

#include <string>
#include <vector>

#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/io/occupancy_raster.h"

namespace hex_slam {
namespace node {

// Returns an empty string and the written paths in `written`, or the error (then nothing was
// written and `written` is empty).
std::string SaveMapFiles(const std::string& base, const io::OccupancyRaster& raster,
                         const io::HexMapData& hex_map, std::vector<std::string>* written);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_MAP_OUTPUT_MAP_SAVER_H_
