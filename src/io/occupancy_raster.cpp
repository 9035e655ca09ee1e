#include "hex_slam/io/occupancy_raster.h"

#include <cmath>
#include <stdexcept>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace io {

namespace {

// Sampling at pixel centres misses the cells no centre falls in (on the hex lattice a hexagon
// can sit between four pixel centres), and a wall one cell thick then shows gaps that a planner
// drives through. So every occupied cell also marks the pixel holding its own centre.
//
// Every other row of hex centres lies on a pixel edge. Rounding put some just below it and
// their neighbours just above the next, two pixels apart: a gap. So a centre within
// kEdgeTolerance of an edge always goes to the pixel above or to the right of it.
constexpr double kEdgeTolerance = 1e-6;  // pixels; rounding errs by ~1e-12

template <class Lattice>
void MarkOccupiedCentres(const LogOddsGrid<Lattice>& grid, OccupancyRaster* raster) {
  const double inv = 1.0 / raster->resolution;
  grid.ForEachKnown([&](std::size_t, const GridIndex& index, float log_odds) {
    if (!(log_odds > 0.0f)) return;
    const Eigen::Vector2d q =
        (grid.lattice().CentreOf(index) - raster->origin) * inv +
        Eigen::Vector2d::Constant(kEdgeTolerance);
    const bool inside =
        q.x() >= 0.0 && q.y() >= 0.0 && q.x() < raster->width && q.y() < raster->height;
    if (!inside) return;
    const int col = static_cast<int>(q.x());
    const int row = static_cast<int>(q.y());
    raster->data[static_cast<std::size_t>(row) * raster->width + col] =
        OccupancyRaster::kOccupied;
  });
}

}  // namespace

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
  // Pixel centres on multiples of the resolution: a square lattice's cell centres, so at its own
  // spacing each pixel is one cell. Corners there instead put every pixel centre on a cell
  // boundary, where rounding picked one neighbour or the other and dropped whole rows of cells.
  const Eigen::Vector2d lo =
      ((box.min() / resolution).array() + 0.5).floor().matrix() * resolution -
      Eigen::Vector2d::Constant(0.5 * resolution);
  const Eigen::Vector2d hi =
      ((box.max() / resolution).array() - 0.5).ceil().matrix() * resolution +
      Eigen::Vector2d::Constant(0.5 * resolution);
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
  MarkOccupiedCentres(grid, &raster);
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
