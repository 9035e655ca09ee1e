// A world drawn as an occupancy image (map_server's YAML + image, as stage's bitmap floorplans):
// every occupied pixel is a solid square. Rays are cast exactly: a walk over the pixels a ray
// crosses (Amanatides–Woo), returning the distance to the boundary of the first occupied one.
#ifndef HEX_SLAM_SIM_IMAGE_WORLD_H_
#define HEX_SLAM_SIM_IMAGE_WORLD_H_

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/io/occupancy_raster.h"
#include "hex_slam/sim/world.h"

namespace hex_slam {
namespace sim {

struct ImageWorldOptions {
  // A pixel is solid when its occupancy (0..100) reaches this value.
  int occupied_threshold = 50;
  // Unknown pixels (-1) are solid too when set; map_server maps of the real world leave the
  // outside unknown, and a simulated beam should not see through it.
  bool unknown_is_occupied = false;
};

class ImageWorld : public World {
 public:
  ImageWorld() = default;
  ImageWorld(const io::OccupancyRaster& raster, const ImageWorldOptions& options);

  // Distance to the boundary of the first solid pixel along the ray; 0 when `origin` lies in a
  // solid pixel; +inf if the ray leaves the image or passes max_range first. Outside the image
  // everything is free.
  double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const override;

  bool IsSolid(int col, int row) const {
    return solid_[static_cast<std::size_t>(row) * width_ + col] != 0;
  }
  bool IsSolidAt(const Eigen::Vector2d& point) const;
  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Eigen::Vector2d& origin() const { return origin_; }
  Eigen::AlignedBox2d Extent() const;

 private:
  double resolution_ = 1.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // lower-left corner of pixel (0, 0)
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> solid_;  // row 0 at the bottom, as in the raster
};

// Loads a map_server YAML and its image. Returns an empty string or an error naming the file.
std::string LoadImageWorld(const std::string& yaml_path, const ImageWorldOptions& options,
                           ImageWorld* world);

// Loads a bare image as stage does a bitmap floorplan: pixels darker than mid-gray are solid,
// `resolution` metres per pixel, the image's lower-left corner at `origin`.
std::string LoadBitmapWorld(const std::string& image_path, double resolution,
                            const Eigen::Vector2d& origin, ImageWorld* world);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_IMAGE_WORLD_H_
