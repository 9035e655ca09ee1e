#include "map_output/map_saver.h"

#include "hex_slam/io/map_server_io.h"

namespace hex_slam {
namespace node {

std::string SaveMapFiles(const std::string& base, const io::OccupancyRaster& raster,
                         const io::HexMapData& hex_map, std::vector<std::string>* written) {
  written->clear();
  io::AtomicFileSet files;
  io::AddMapServerMap(raster, base, &files);
  io::AddHexMapFile(base + ".hexmap", hex_map, &files);
  const std::string error = files.Commit();
  if (error.empty()) *written = {base + ".yaml", base + ".pgm", base + ".hexmap"};
  return error;
}

}  // namespace node
}  // namespace hex_slam
