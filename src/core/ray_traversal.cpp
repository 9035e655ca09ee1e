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
  // bisector the ray crosses. t[j] is the ray parameter where it crosses bisector j of the
  // current cell; stepping to neighbour k moves every bisector j by d·cos(angle between k and
  // j) along its normal, a constant increment, as in Amanatides & Woo's square traversal.
  int forward[3];
  double t[3];
  double inv_rate[3];
  int count = 0;
  const Eigen::Vector2d offset = lattice.CentreOf(cell) - from;
  for (int k = 0; k < 6 && count < 3; ++k) {
    const Eigen::Vector2d n(kNeighbourNx[k], kNeighbourNy[k]);
    const double rate = dir.dot(n);
    if (rate > 1e-12) {
      forward[count] = k;
      inv_rate[count] = 1.0 / rate;
      t[count] = (offset.dot(n) + 0.5 * d) * inv_rate[count];
      ++count;
    }
  }
  double increment[3][3];  // increment[j][i]: change of t[i] when stepping across bisector j
  for (int j = 0; j < count; ++j) {
    for (int i = 0; i < count; ++i) {
      const double cos_angle = kNeighbourNx[forward[j]] * kNeighbourNx[forward[i]] +
                               kNeighbourNy[forward[j]] * kNeighbourNy[forward[i]];
      increment[j][i] = d * cos_angle * inv_rate[i];
    }
  }

  // With two forward sides (a ray along a lattice axis) the third slot never wins.
  if (count == 2) {
    forward[2] = forward[1];
    t[2] = std::numeric_limits<double>::infinity();
    for (int j = 0; j < 3; ++j) increment[j][2] = increment[2][j] = 0.0;
  }
  int step_a[3], step_b[3];
  for (int j = 0; j < 3; ++j) {
    step_a[j] = kNeighbourDa[forward[j]];
    step_b[j] = kNeighbourDb[forward[j]];
  }

  // The exit side changes unpredictably from cell to cell, so it is chosen with selects and table
  // look-ups rather than branches (a mispredicted branch per cell doubles the cost).
  const int step_cap = kMinStepCap + static_cast<int>(kMaxStepsPerSpacing * length / d);
  for (int step = 0; step < step_cap; ++step) {
    crossed->push_back(cell);
    const int first = t[1] < t[0] ? 1 : 0;
    const double t_first = t[1] < t[0] ? t[1] : t[0];
    const int best = t[2] < t_first ? 2 : first;
    const double t_best = t[2] < t_first ? t[2] : t_first;
    if (t_best >= length) return;  // `to` lies in this cell by the walk's own geometry
    cell.a += step_a[best];
    cell.b += step_b[best];
    if (cell == end) return;
    t[0] += increment[best][0];
    t[1] += increment[best][1];
    t[2] += increment[best][2];
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
  // Branch-free choice of the axis to step along, as in the hex walk, so both lattices pay the
  // same for their unpredictable exits.
  for (int step = 0; step < step_cap; ++step) {
    crossed->push_back(cell);
    const bool along_x = next_x < next_y;
    if ((along_x ? next_x : next_y) >= 1.0) return;
    cell.col += along_x ? step_x : 0;
    cell.row += along_x ? 0 : step_y;
    if (cell == end) return;
    next_x += along_x ? delta_x : 0.0;
    next_y += along_x ? 0.0 : delta_y;
  }
}

}  // namespace hex_slam
