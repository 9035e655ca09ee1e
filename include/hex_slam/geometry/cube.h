// Cube coordinates (MATH.md §1, §3, §5): three axes 120° apart, x + y + ζ = 0.
//
// Cartesian (X, Y) maps to its projections on the axes at 0°, 120° and 240°. A cube-space tangent
// vector is sqrt(1.5) times longer than its Cartesian image, so cube norms are never metres.
#ifndef HEX_SLAM_GEOMETRY_CUBE_H_
#define HEX_SLAM_GEOMETRY_CUBE_H_

#include <cmath>
#include <cstdint>

#include <Eigen/Core>

#include "hex_slam/geometry/grid_index.h"

namespace hex_slam {

constexpr double kSqrt3 = 1.7320508075688772935;

// A continuous point on the plane x + y + ζ = 0. The invariant is checked where one is made from
// raw components; the conversions below produce it by construction.
class CubePoint {
 public:
  CubePoint() = default;
  // Throws std::invalid_argument when |x + y + z| exceeds `tolerance`.
  static CubePoint FromComponents(double x, double y, double z, double tolerance = 1e-9);
  static CubePoint FromCartesian(const Eigen::Vector2d& p);
  // A lidar return at range r and bearing phi (paper eq. 2).
  static CubePoint FromPolar(double range, double bearing);

  Eigen::Vector2d ToCartesian() const;
  const Eigen::Vector3d& vector() const { return v_; }
  double x() const { return v_.x(); }
  double y() const { return v_.y(); }
  double z() const { return v_.z(); }

 private:
  explicit CubePoint(const Eigen::Vector3d& v) : v_(v) {}
  Eigen::Vector3d v_ = Eigen::Vector3d::Zero();
};

// Cartesian <-> cube for raw vectors, used in the matcher's inner loop.
inline Eigen::Vector3d CartesianToCube(double X, double Y) {
  return {X, -0.5 * X + 0.5 * kSqrt3 * Y, -0.5 * X - 0.5 * kSqrt3 * Y};
}
inline Eigen::Vector2d CubeToCartesian(const Eigen::Vector3d& c) {
  return {c.x(), (c.y() - c.z()) / kSqrt3};
}

// An integer lattice point (a, b, c) with a + b + c = 0, stored as its axial pair (a, b).
struct HexCell {
  int a = 0;
  int b = 0;
  int c() const { return -a - b; }
  bool operator==(const HexCell& o) const { return a == o.a && b == o.b; }
  bool operator!=(const HexCell& o) const { return !(*this == o); }
};

// std::round (halves away from zero) without its library call, for the lattice's hottest line:
// every endpoint of every match, insertion and search is rounded here. Exact: below 2^52 a
// double's fraction x - trunc(x) is representable, and from there on every double is whole.
inline double RoundHalfAway(double x) {
  constexpr double kAllWhole = 4503599627370496.0;  // 2^52
  if (!(std::abs(x) < kAllWhole)) return std::round(x);  // NaN, infinities, huge: the library's
  const double whole = static_cast<double>(static_cast<std::int64_t>(x));  // toward zero
  const double fraction = x - whole;
  if (fraction >= 0.5) return whole + 1.0;
  if (fraction <= -0.5) return whole - 1.0;
  return whole;
}

// Paper Algorithm 1: the lattice point nearest to `u` (lattice units, u.x+u.y+u.z = 0). The
// coordinate whose rounding moved furthest is the one recomputed from the other two. Inline:
// called once per endpoint per candidate pose, out of line it cost a call through the PLT each.
inline HexCell RoundCube(const Eigen::Vector3d& u) {
  double rx = RoundHalfAway(u.x());
  double ry = RoundHalfAway(u.y());
  double rz = RoundHalfAway(u.z());
  const double dx = std::abs(rx - u.x());
  const double dy = std::abs(ry - u.y());
  const double dz = std::abs(rz - u.z());
  if (dx > dy && dx > dz) {
    rx = -ry - rz;
  } else if (dy > dz) {
    ry = -rx - rz;
  }
  // When the rounded triple already sums to zero the resets above change nothing, so the
  // paper's separate first branch is not needed.
  // Clamped so that a NaN, infinite or huge u names a cell outside every map (grid_index.h).
  return HexCell{static_cast<int>(ClampToIndexRange(rx)), static_cast<int>(ClampToIndexRange(ry))};
}

// Rotation by psi about (1,1,1)/sqrt(3); counter-clockwise in Cartesian terms (paper eq. 10).
Eigen::Matrix3d CubeRotation(double psi);

// d/dpsi of CubeRotation(psi) * s, written out as MATH.md §5 gives it.
Eigen::Vector3d CubeRotationDerivative(const Eigen::Vector3d& s, double psi);

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_CUBE_H_
