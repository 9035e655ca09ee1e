#include "hex_slam/io/map_image.h"

#include <algorithm>
#include <cmath>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace io {
namespace {

constexpr double kPixelsPerCell = 8.0;
constexpr Rgb kUnknown = {214, 218, 228};
constexpr double kOutlineShade = 0.82;  // boundary pixels keep this fraction of their brightness
// Pictures beyond this many pixels per side are scaled down to it.
constexpr int kMaxSide = 8000;

Rgb Shade(float probability) {
  const auto v = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - probability)));
  return {v, v, v};
}

void Put(Image* image, int x, int y, const Rgb& colour) {
  if (x < 0 || y < 0 || x >= image->width || y >= image->height) return;
  std::uint8_t* p = image->at(x, y);
  p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
}

}  // namespace

ImageFrame ImageFrame::Covering(const Eigen::AlignedBox2d& box, double pixels_per_metre) {
  ImageFrame frame;
  const Eigen::Vector2d size = box.sizes();
  const double largest = std::max(size.x(), size.y());
  if (largest * pixels_per_metre > kMaxSide) pixels_per_metre = kMaxSide / largest;
  frame.pixels_per_metre = pixels_per_metre;
  frame.world_min = box.min();
  frame.width = std::max(1, static_cast<int>(std::ceil(size.x() * pixels_per_metre)));
  frame.height = std::max(1, static_cast<int>(std::ceil(size.y() * pixels_per_metre)));
  return frame;
}

Eigen::Vector2d ImageFrame::ToPixel(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d p = (world - world_min) * pixels_per_metre;
  return {p.x(), height - p.y()};
}

Eigen::Vector2d ImageFrame::ToWorld(double px, double py) const {
  return world_min + Eigen::Vector2d(px + 0.5, height - (py + 0.5)) / pixels_per_metre;
}

template <class Lattice>
Image RenderMap(const GridMap<Lattice>& grid, const MapImageOptions& options, ImageFrame* frame) {
  Eigen::AlignedBox2d box = grid.KnownExtent();
  if (box.isEmpty()) box = Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  const Eigen::Vector2d pad = Eigen::Vector2d::Constant(options.margin);
  box = Eigen::AlignedBox2d(box.min() - pad, box.max() + pad);
  const double ppm = options.pixels_per_metre > 0.0 ? options.pixels_per_metre
                                                    : kPixelsPerCell / grid.lattice().spacing();
  *frame = ImageFrame::Covering(box, ppm);
  Image image(frame->width, frame->height, 3);
  // One row of cells at a time: the cell under each pixel, then its colour.
  std::vector<typename Lattice::Cell> above(frame->width), current(frame->width);
  for (int y = 0; y < frame->height; ++y) {
    for (int x = 0; x < frame->width; ++x) {
      current[x] = grid.lattice().CellOf(frame->ToWorld(x, y));
    }
    for (int x = 0; x < frame->width; ++x) {
      const auto& cell = current[x];
      const bool known = grid.LogOdds(cell) != 0.0f;
      Rgb colour = known ? Shade(grid.Probability(cell)) : kUnknown;
      const bool boundary = (x > 0 && current[x - 1] != cell) || (y > 0 && above[x] != cell);
      if (options.cell_outlines && known && boundary) {
        for (auto& c : colour) c = static_cast<std::uint8_t>(c * kOutlineShade);
      }
      Put(&image, x, y, colour);
    }
    std::swap(above, current);
  }
  return image;
}

template Image RenderMap(const GridMap<HexLattice>&, const MapImageOptions&, ImageFrame*);
template Image RenderMap(const GridMap<SquareLattice>&, const MapImageOptions&, ImageFrame*);

void DrawDisc(const ImageFrame& frame, const Eigen::Vector2d& centre, int radius_px,
              const Rgb& colour, Image* image) {
  const Eigen::Vector2d c = frame.ToPixel(centre);
  for (int dy = -radius_px; dy <= radius_px; ++dy) {
    for (int dx = -radius_px; dx <= radius_px; ++dx) {
      if (dx * dx + dy * dy <= radius_px * radius_px) {
        Put(image, static_cast<int>(c.x()) + dx, static_cast<int>(c.y()) + dy, colour);
      }
    }
  }
}

void DrawPolyline(const ImageFrame& frame, const std::vector<Eigen::Vector2d>& points,
                  const Rgb& colour, int thickness, Image* image) {
  const int radius = std::max(0, thickness / 2);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Eigen::Vector2d a = frame.ToPixel(points[i - 1]);
    const Eigen::Vector2d b = frame.ToPixel(points[i]);
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm())));
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(s) / steps);
      for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
          Put(image, static_cast<int>(p.x()) + dx, static_cast<int>(p.y()) + dy, colour);
        }
      }
    }
  }
}

}  // namespace io
}  // namespace hex_slam
