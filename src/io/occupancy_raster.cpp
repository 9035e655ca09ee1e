#include "hex_slam/io/occupancy_raster.h"

#include <cmath>
#include <stdexcept>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace io {

template <class Lattice>
OccupancyRaster Rasterize(const LogOddsGrid<Lattice>& grid, double resolution,
                          const Eigen::AlignedBox2d& region) {
  if (!(resolution > 0.0)) throw std::invalid_argument("Rasterize: resolution must be > 0");
  OccupancyRaster raster;
  raster.resolution = resolution;
  Eigen::AlignedBox2d box = region;
  if (box.isEmpty()) {
    box = grid.KnownExtent();
    if (box.isEmpty()) return raster;
    const Eigen::Vector2d pad = Eigen::Vector2d::Constant(grid.lattice().spacing() + resolution);
    box = Eigen::AlignedBox2d(box.min() - pad, box.max() + pad);
  }
  const Eigen::Vector2d lo = (box.min() / resolution).array().floor().matrix() * resolution;
  const Eigen::Vector2d hi = (box.max() / resolution).array().ceil().matrix() * resolution;
  raster.origin = lo;
  raster.width = std::max(1, static_cast<int>(std::lround((hi.x() - lo.x()) / resolution)));
  raster.height = std::max(1, static_cast<int>(std::lround((hi.y() - lo.y()) / resolution)));
  raster.data.assign(static_cast<std::size_t>(raster.width) * raster.height,
                     OccupancyRaster::kUnknown);
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const float log_odds = grid.LogOdds(grid.lattice().CellOf(raster.PixelCentre(col, row)));
      std::int8_t& value = raster.data[static_cast<std::size_t>(row) * raster.width + col];
      if (log_odds > 0.0f) {
        value = OccupancyRaster::kOccupied;
      } else if (log_odds < 0.0f) {
        value = OccupancyRaster::kFree;
      }
    }
  }
  return raster;
}

OccupancyRaster EmptyRaster(double resolution) {
  OccupancyRaster raster;
  raster.resolution = resolution;
  raster.origin = Eigen::Vector2d::Constant(-0.5 * resolution);
  raster.width = raster.height = 1;
  raster.data.assign(1, OccupancyRaster::kUnknown);
  return raster;
}

template OccupancyRaster Rasterize(const LogOddsGrid<HexLattice>&, double,
                                   const Eigen::AlignedBox2d&);
template OccupancyRaster Rasterize(const LogOddsGrid<SquareLattice>&, double,
                                   const Eigen::AlignedBox2d&);

}  // namespace io
}  // namespace hex_slam
