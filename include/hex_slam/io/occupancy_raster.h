// A square raster of occupancy values in nav_msgs/OccupancyGrid's convention (-1 unknown,
// 0 free ... 100 occupied, row-major from the lower-left cell), and the resampling of any
// lattice's grid onto it: each pixel takes the value of the lattice cell containing its centre,
// and every occupied cell also marks the pixel containing its own centre, so no wall cell is
// lost between pixel centres.
#ifndef HEX_SLAM_IO_OCCUPANCY_RASTER_H_
#define HEX_SLAM_IO_OCCUPANCY_RASTER_H_

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/map/log_odds_grid.h"

namespace hex_slam {
namespace io {

struct OccupancyRaster {
  static constexpr std::int8_t kUnknown = -1;
  static constexpr std::int8_t kFree = 0;
  static constexpr std::int8_t kOccupied = 100;

  double resolution = 0.05;                        // m per pixel
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // lower-left corner of pixel (0, 0)
  int width = 0;
  int height = 0;
  std::vector<std::int8_t> data;  // width * height, row 0 at the bottom

  std::int8_t at(int col, int row) const { return data[static_cast<std::size_t>(row) * width + col]; }
  Eigen::Vector2d PixelCentre(int col, int row) const {
    return origin + resolution * Eigen::Vector2d(col + 0.5, row + 0.5);
  }
};

// hector's three-valued read-out: log-odds > 0 occupied, < 0 free, 0 unknown. `region` limits the
// raster (default: every cell ever observed, plus one pixel); it snaps to the pixel grid whose
// pixel centres lie on multiples of `resolution` (a square lattice's cell centres), so
// consecutive rasters of a growing map line up.
template <class Lattice>
OccupancyRaster Rasterize(const LogOddsGrid<Lattice>& grid, double resolution,
                          const Eigen::AlignedBox2d& region = Eigen::AlignedBox2d());

// A map with nothing in it: one unknown pixel at the origin (consumers such as rviz reject
// zero-sized grids).
OccupancyRaster EmptyRaster(double resolution);

// The raster pixel the map files and /map use: the lattice's spacing (map_resolution), the
// pixel hector_mapping's users expect.
template <class Lattice>
double MapResolution(const Lattice& lattice) {
  return lattice.spacing();
}

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_OCCUPANCY_RASTER_H_
