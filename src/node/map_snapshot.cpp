#include "map_snapshot.h"

namespace hex_slam {
namespace node {
namespace {

template <class Lattice>
io::OccupancyRaster RasterizeGrid(const GridMap<Lattice>& grid) {
  const double resolution = io::EqualAreaResolution(grid.lattice());
  io::OccupancyRaster raster = io::Rasterize(grid, resolution);
  if (raster.data.empty()) {
    raster.resolution = resolution;
    raster.origin = Eigen::Vector2d::Constant(-0.5 * resolution);
    raster.width = raster.height = 1;
    raster.data.assign(1, io::OccupancyRaster::kUnknown);
  }
  return raster;
}

}  // namespace

MapSnapshot TakeSnapshot(const Slam& slam, std::uint64_t generation) {
  MapSnapshot snapshot;
  snapshot.generation = generation;
  if (slam.hex_maps()) snapshot.hex.emplace(slam.hex_maps()->level(0));
  if (slam.square_maps()) snapshot.square.emplace(slam.square_maps()->level(0));
  return snapshot;
}

io::OccupancyRaster RasterizeSnapshot(const MapSnapshot& snapshot) {
  return snapshot.hex ? RasterizeGrid(*snapshot.hex) : RasterizeGrid(*snapshot.square);
}

}  // namespace node
}  // namespace hex_slam
