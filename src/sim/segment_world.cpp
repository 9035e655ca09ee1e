#include "hex_slam/sim/segment_world.h"

#include <cmath>
#include <limits>

namespace hex_slam {
namespace sim {

void SegmentWorld::AddSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  segments_.emplace_back(a, b);
}

void SegmentWorld::AddRectangle(const Eigen::Vector2d& min, const Eigen::Vector2d& max) {
  const Eigen::Vector2d c1(max.x(), min.y()), c3(min.x(), max.y());
  AddSegment(min, c1);
  AddSegment(c1, max);
  AddSegment(max, c3);
  AddSegment(c3, min);
}

double SegmentWorld::CastRay(const Eigen::Vector2d& origin, double angle,
                             double max_range) const {
  const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : segments_) {
    const Eigen::Vector2d e = b - a;
    const double denom = dir.x() * e.y() - dir.y() * e.x();
    if (std::abs(denom) < 1e-15) continue;  // parallel
    const Eigen::Vector2d w = a - origin;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
    const double u = (w.x() * dir.y() - w.y() * dir.x()) / denom;
    if (t > 0.0 && u >= 0.0 && u <= 1.0 && t < best) best = t;
  }
  return best <= max_range ? best : std::numeric_limits<double>::infinity();
}

SegmentWorld SegmentWorld::Transformed(const Pose2& placement) const {
  SegmentWorld moved;
  for (const auto& [a, b] : segments_) moved.AddSegment(placement * a, placement * b);
  return moved;
}

SegmentWorld SegmentWorld::TestRoom() {
  SegmentWorld w;
  w.AddRectangle({-5.0, -4.0}, {5.0, 4.0});
  // A dividing wall with a door, an alcove, pillars and boxes of different sizes.
  w.AddSegment({1.5, -4.0}, {1.5, -1.0});
  w.AddSegment({1.5, 0.2}, {1.5, 1.5});
  w.AddSegment({-5.0, 2.0}, {-3.5, 2.0});
  w.AddRectangle({-2.6, -2.4}, {-2.0, -1.8});
  w.AddRectangle({3.0, 2.2}, {3.8, 2.6});
  w.AddRectangle({-1.0, 2.6}, {-0.6, 3.0});
  w.AddRectangle({3.2, -3.0}, {4.0, -2.2});
  w.AddSegment({-4.2, -3.0}, {-3.0, -4.0});
  return w;
}

}  // namespace sim
}  // namespace hex_slam
