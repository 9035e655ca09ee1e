#include "hex_slam/sim/image_world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hex_slam/io/image_io.h"
#include "hex_slam/io/map_server_io.h"

namespace hex_slam {
namespace sim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// stage's bitmap rule: a pixel darker than this is an obstacle.
constexpr int kBitmapSolidBelowGray = 128;

}  // namespace

ImageWorld::ImageWorld(const io::OccupancyRaster& raster, const ImageWorldOptions& options)
    : resolution_(raster.resolution),
      origin_(raster.origin),
      width_(raster.width),
      height_(raster.height) {
  if (!(raster.resolution > 0.0) || raster.width <= 0 || raster.height <= 0 ||
      raster.data.size() != static_cast<std::size_t>(raster.width) * raster.height) {
    throw std::invalid_argument("ImageWorld: empty or inconsistent raster");
  }
  solid_.resize(raster.data.size());
  for (std::size_t i = 0; i < raster.data.size(); ++i) {
    const int v = raster.data[i];
    solid_[i] = v == io::OccupancyRaster::kUnknown ? options.unknown_is_occupied
                                                   : v >= options.occupied_threshold;
  }
}

Eigen::AlignedBox2d ImageWorld::Extent() const {
  return Eigen::AlignedBox2d(origin_,
                             origin_ + resolution_ * Eigen::Vector2d(width_, height_));
}

bool ImageWorld::IsSolidAt(const Eigen::Vector2d& point) const {
  const Eigen::Vector2d u = (point - origin_) / resolution_;
  const double col = std::floor(u.x()), row = std::floor(u.y());
  if (col < 0 || row < 0 || col >= width_ || row >= height_) return false;
  return IsSolid(static_cast<int>(col), static_cast<int>(row));
}

double ImageWorld::CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const {
  if (solid_.empty()) return kInfinity;
  const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
  // Work in pixel units: pixel (c, r) is [c, c+1) × [r, r+1); t stays in metres.
  const Eigen::Vector2d o = (origin - origin_) / resolution_;
  const Eigen::Vector2d d = dir / resolution_;  // pixels per metre along the ray

  // Clip the ray to the image (slab test); outside it everything is free.
  double t_enter = 0.0, t_exit = max_range;
  const double size[2] = {static_cast<double>(width_), static_cast<double>(height_)};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < 0.0 || o[k] >= size[k]) return kInfinity;
      continue;
    }
    double t0 = (0.0 - o[k]) / d[k], t1 = (size[k] - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
  }
  if (t_enter > t_exit) return kInfinity;

  // The pixel containing the entry point; clamped because the entry lies on the image's edge.
  const Eigen::Vector2d start = o + t_enter * d;
  int col = std::min(width_ - 1, std::max(0, static_cast<int>(std::floor(start.x()))));
  int row = std::min(height_ - 1, std::max(0, static_cast<int>(std::floor(start.y()))));
  const int step_col = d.x() > 0.0 ? 1 : -1;
  const int step_row = d.y() > 0.0 ? 1 : -1;
  // Distance to the next column / row boundary, computed from the boundary itself every step so
  // no rounding accumulates along long rays.
  const double inv_dx = d.x() != 0.0 ? 1.0 / d.x() : kInfinity;
  const double inv_dy = d.y() != 0.0 ? 1.0 / d.y() : kInfinity;
  const auto next_col_t = [&](int c) {
    return d.x() != 0.0 ? ((c + (step_col > 0 ? 1 : 0)) - o.x()) * inv_dx : kInfinity;
  };
  const auto next_row_t = [&](int r) {
    return d.y() != 0.0 ? ((r + (step_row > 0 ? 1 : 0)) - o.y()) * inv_dy : kInfinity;
  };
  double t = t_enter;
  double t_col = next_col_t(col), t_row = next_row_t(row);
  while (true) {
    if (IsSolid(col, row)) return t <= max_range ? t : kInfinity;
    if (t_col < t_row) {
      t = t_col;
      col += step_col;
      if (col < 0 || col >= width_) return kInfinity;
      t_col = next_col_t(col);
    } else {
      t = t_row;
      row += step_row;
      if (row < 0 || row >= height_) return kInfinity;
      t_row = next_row_t(row);
    }
    if (t > max_range) return kInfinity;
  }
}

std::string LoadImageWorld(const std::string& yaml_path, const ImageWorldOptions& options,
                           ImageWorld* world) {
  io::OccupancyRaster raster;
  const std::string error = io::LoadMapServerMap(yaml_path, &raster);
  if (!error.empty()) return error;
  if (raster.width <= 0 || raster.height <= 0) return yaml_path + ": the image is empty";
  *world = ImageWorld(raster, options);
  return "";
}

std::string LoadBitmapWorld(const std::string& image_path, double resolution,
                            const Eigen::Vector2d& origin, ImageWorld* world) {
  if (!(resolution > 0.0) || !origin.allFinite()) {
    return image_path + ": resolution must be > 0 and the origin finite";
  }
  io::Image image;
  const std::string error = io::ReadGrayImage(image_path, &image);
  if (!error.empty()) return error;
  if (image.width <= 0 || image.height <= 0) return image_path + ": the image is empty";
  io::OccupancyRaster raster;
  raster.resolution = resolution;
  raster.origin = origin;
  raster.width = image.width;
  raster.height = image.height;
  raster.data.resize(static_cast<std::size_t>(image.width) * image.height);
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const bool solid = *image.at(col, image.height - 1 - row) < kBitmapSolidBelowGray;
      raster.data[static_cast<std::size_t>(row) * image.width + col] =
          solid ? io::OccupancyRaster::kOccupied : io::OccupancyRaster::kFree;
    }
  }
  *world = ImageWorld(raster, ImageWorldOptions());
  return "";
}

}  // namespace sim
}  // namespace hex_slam
