#include "map_saver.h"

#include "hex_slam/io/map_server_io.h"

namespace hex_slam {
namespace node {

std::string SaveMapFiles(const std::string& base, const io::OccupancyRaster& raster,
                         const io::HexMapData& hex_map, std::vector<std::string>* written) {
  written->clear();
  std::string error = io::SaveMapServerMap(raster, base);
  if (!error.empty()) return error;
  written->push_back(base + ".yaml");
  written->push_back(base + ".pgm");
  error = io::WriteHexMapFile(base + ".hexmap", hex_map);
  if (!error.empty()) return error;
  written->push_back(base + ".hexmap");
  return "";
}

}  // namespace node
}  // namespace hex_slam
