// map_server's map format (YAML metadata + image), which Debian does not package: written the way
// map_saver writes it and read the way map_server reads it, so saved maps load in either.
#ifndef HEX_SLAM_IO_MAP_SERVER_IO_H_
#define HEX_SLAM_IO_MAP_SERVER_IO_H_

#include <string>

#include "hex_slam/io/atomic_file.h"
#include "hex_slam/io/occupancy_raster.h"

namespace hex_slam {
namespace io {

// map_saver's thresholds and gray levels.
struct MapServerFormat {
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  static constexpr int kOccupiedGray = 0;
  static constexpr int kFreeGray = 254;
  static constexpr int kUnknownGray = 205;
};

// Writes `<base>.pgm` and `<base>.yaml`, both or neither (atomic_file.h). Returns an empty string
// or an error.
std::string SaveMapServerMap(const OccupancyRaster& raster, const std::string& base);
// The same as two files of a larger set written together.
void AddMapServerMap(const OccupancyRaster& raster, const std::string& base, AtomicFileSet* files);

// Reads a map_server YAML (modes trinary, scale and raw; negate; origin yaw must be 0) and the
// image it names, relative to the YAML's folder. Returns an empty string or an error naming what
// is wrong.
std::string LoadMapServerMap(const std::string& yaml_path, OccupancyRaster* raster);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_MAP_SERVER_IO_H_
