#include "hex_slam/sensor/grazing_endpoints.h"

#include <algorithm>
#include <cmath>

namespace hex_slam {
namespace {

// Three points on one straight surface, sampled by beams a fixed angle apart, have gaps that
// differ by the change of range between them (a few tens of percent even when grazing), and the
// middle one within its range noise of the chord. A depth jump has one gap many times the other;
// a corner bends the chord.
constexpr double kMaxGapRatio = 2.0;
constexpr double kMaxChordOffset = 0.2;  // of the chord's length

bool OnStraightStretch(const Eigen::Vector2d& before, const Eigen::Vector2d& p,
                       const Eigen::Vector2d& after) {
  const double a = (p - before).norm(), b = (after - p).norm();
  const double chord = (after - before).norm();
  return std::max(a, b) < kMaxGapRatio * std::min(a, b) &&
         (p - 0.5 * (before + after)).norm() < kMaxChordOffset * chord;
}

}  // namespace

int MarkGrazingEndpoints(const std::vector<Eigen::Vector2d>& points, double max_incidence,
                          std::vector<bool>* grazing) {
  grazing->assign(points.size(), false);
  if (!(max_incidence < 0.5 * M_PI) || points.size() < 3) return 0;
  // The incidence α from the normal is past the limit when the beam lies within π/2 - α of the
  // surface: |cos(beam, surface)| > sin(max_incidence).
  const double min_cos_to_surface = std::sin(max_incidence);
  int marked = 0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    if (!OnStraightStretch(points[i - 1], p, points[i + 1])) continue;
    const Eigen::Vector2d along = points[i + 1] - points[i - 1];
    const double lengths = along.norm() * p.norm();
    if (lengths > 0.0 && std::abs(along.dot(p)) > min_cos_to_surface * lengths) {
      (*grazing)[i] = true;
      ++marked;
    }
  }
  return marked;
}

}  // namespace hex_slam
