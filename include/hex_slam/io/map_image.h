// Pictures of maps: every pixel takes the occupancy of the lattice cell under it, and pixels on a
// cell boundary are darkened, so a hex map is drawn as actual hexagons. Trajectories and points
// can be drawn on top in world coordinates.
#ifndef HEX_SLAM_IO_MAP_IMAGE_H_
#define HEX_SLAM_IO_MAP_IMAGE_H_

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/io/image_io.h"

namespace hex_slam {
namespace io {

using Rgb = std::array<std::uint8_t, 3>;

// Where the world sits in a picture: pixel (0, 0) is the top-left, world +y points up.
struct ImageFrame {
  Eigen::Vector2d world_min = Eigen::Vector2d::Zero();  // bottom-left corner of the picture
  double pixels_per_metre = 100.0;
  int width = 0;
  int height = 0;

  static ImageFrame Covering(const Eigen::AlignedBox2d& box, double pixels_per_metre);
  Eigen::Vector2d ToPixel(const Eigen::Vector2d& world) const;
  Eigen::Vector2d ToWorld(double px, double py) const;  // pixel centre -> world
};

struct MapImageOptions {
  double pixels_per_metre = 0.0;  // 0: about 8 pixels across a cell
  bool cell_outlines = true;      // draw the lattice (only where cells are known)
  double margin = 0.2;            // m of unknown around the known area
};

// Renders the observed part of `grid` (free white, occupied black, grey levels between, unknown
// light grey-blue). `frame` receives the mapping for drawing overlays.
template <class Lattice>
Image RenderMap(const GridMap<Lattice>& grid, const MapImageOptions& options, ImageFrame* frame);

void DrawPolyline(const ImageFrame& frame, const std::vector<Eigen::Vector2d>& points,
                  const Rgb& colour, int thickness, Image* image);
void DrawDisc(const ImageFrame& frame, const Eigen::Vector2d& centre, int radius_px,
              const Rgb& colour, Image* image);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_MAP_IMAGE_H_
