#include "hex_slam/ray_traversal.h"

#include <cmath>
#include <limits>

namespace hex_slam {
namespace {

// The six neighbour steps in axial coordinates and their Cartesian directions (flat-top cells):
// -30°, 30°, 90°, 150°, 210°, 270°.
constexpr int kNeighbourDa[6] = {1, 1, 0, -1, -1, 0};
constexpr int kNeighbourDb[6] = {-1, 0, 1, 1, 0, -1};
constexpr double kHalfSqrt3 = 0.5 * kSqrt3;
constexpr double kNeighbourNx[6] = {kHalfSqrt3, kHalfSqrt3, 0.0, -kHalfSqrt3, -kHalfSqrt3, 0.0};
constexpr double kNeighbourNy[6] = {-0.5, 0.5, 1.0, 0.5, -0.5, -1.0};

// A safety cap on the walk: a segment of length L crosses at most about 2L/d + 2 hexagons.
constexpr double kMaxStepsPerSpacing = 4.0;
constexpr int kMinStepCap = 8;

}  // namespace

void TraceRay(const HexLattice& lattice, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
              std::vector<HexCell>* crossed) {
  crossed->clear();
  HexCell cell = lattice.CellOf(from);
  const HexCell end = lattice.CellOf(to);
  if (cell == end) return;

  const Eigen::Vector2d delta = to - from;
  const double length = delta.norm();
  const Eigen::Vector2d dir = delta / length;
  const double d = lattice.spacing();

  // Only neighbours the ray moves towards can be exit sides; the hexagon is the intersection of
  // the half-planes "closer to this centre than to neighbour k", so the exit is the first
  // bisector the ray crosses.
  int forward[3];
  double inv_rate[3];
  Eigen::Vector2d normal[3];
  int count = 0;
  for (int k = 0; k < 6 && count < 3; ++k) {
    const Eigen::Vector2d n(kNeighbourNx[k], kNeighbourNy[k]);
    const double rate = dir.dot(n);
    if (rate > 1e-12) {
      forward[count] = k;
      normal[count] = n;
      inv_rate[count] = 1.0 / rate;
      ++count;
    }
  }

  const int step_cap = kMinStepCap + static_cast<int>(kMaxStepsPerSpacing * length / d);
  for (int step = 0; step < step_cap; ++step) {
    crossed->push_back(cell);
    const Eigen::Vector2d offset = lattice.CentreOf(cell) - from;
    double best_t = std::numeric_limits<double>::infinity();
    int best = 0;
    for (int j = 0; j < count; ++j) {
      const double t = (offset.dot(normal[j]) + 0.5 * d) * inv_rate[j];
      if (t < best_t) {
        best_t = t;
        best = forward[j];
      }
    }
    if (best_t >= length) return;  // `to` lies in this cell by the walk's own geometry
    cell = HexCell{cell.a + kNeighbourDa[best], cell.b + kNeighbourDb[best]};
    if (cell == end) return;
  }
}

void TraceRay(const SquareLattice& lattice, const Eigen::Vector2d& from,
              const Eigen::Vector2d& to, std::vector<GridIndex>* crossed) {
  crossed->clear();
  // Amanatides & Woo in cell units, where cell i spans [i - 1/2, i + 1/2).
  const double inv = lattice.inv_side();
  const Eigen::Vector2d p0 = from * inv + Eigen::Vector2d(0.5, 0.5);
  const Eigen::Vector2d p1 = to * inv + Eigen::Vector2d(0.5, 0.5);
  GridIndex cell{static_cast<int>(std::floor(p0.x())), static_cast<int>(std::floor(p0.y()))};
  const GridIndex end = lattice.CellOf(to);
  if (cell == end) return;

  const Eigen::Vector2d d = p1 - p0;
  const int step_x = d.x() > 0 ? 1 : -1;
  const int step_y = d.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const double delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : inf;
  const double delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : inf;
  double next_x = d.x() != 0.0 ? ((step_x > 0 ? cell.col + 1 - p0.x() : p0.x() - cell.col) *
                                  delta_x)
                               : inf;
  double next_y = d.y() != 0.0 ? ((step_y > 0 ? cell.row + 1 - p0.y() : p0.y() - cell.row) *
                                  delta_y)
                               : inf;
  const int step_cap = kMinStepCap + std::abs(end.col - cell.col) + std::abs(end.row - cell.row);
  for (int step = 0; step < step_cap; ++step) {
    crossed->push_back(cell);
    if (next_x < next_y) {
      if (next_x >= 1.0) return;
      cell.col += step_x;
      next_x += delta_x;
    } else {
      if (next_y >= 1.0) return;
      cell.row += step_y;
      next_y += delta_y;
    }
    if (cell == end) return;
  }
}

}  // namespace hex_slam
