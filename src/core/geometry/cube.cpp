#include "hex_slam/geometry/cube.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "hex_slam/geometry/grid_index.h"

namespace hex_slam {

CubePoint CubePoint::FromComponents(double x, double y, double z, double tolerance) {
  if (!(std::abs(x + y + z) <= tolerance)) {
    throw std::invalid_argument("CubePoint: x + y + z = " + std::to_string(x + y + z) +
                                ", must be 0");
  }
  return CubePoint(Eigen::Vector3d(x, y, z));
}

CubePoint CubePoint::FromCartesian(const Eigen::Vector2d& p) {
  return CubePoint(CartesianToCube(p.x(), p.y()));
}

CubePoint CubePoint::FromPolar(double range, double bearing) {
  return CubePoint(Eigen::Vector3d(range * std::cos(bearing),
                                   range * std::cos(2.0 * M_PI / 3.0 - bearing),
                                   range * std::cos(4.0 * M_PI / 3.0 - bearing)));
}

Eigen::Vector2d CubePoint::ToCartesian() const { return CubeToCartesian(v_); }

namespace {

// std::round (halves away from zero) without its library call, for the lattice's hottest line:
// every endpoint of every match, insertion and search is rounded here. Exact: below 2^52 a
// double's fraction x - trunc(x) is representable, and from there on every double is whole.
double RoundHalfAway(double x) {
  constexpr double kAllWhole = 4503599627370496.0;  // 2^52
  if (!(std::abs(x) < kAllWhole)) return std::round(x);  // NaN, infinities, huge: the library's
  const double whole = static_cast<double>(static_cast<std::int64_t>(x));  // toward zero
  const double fraction = x - whole;
  if (fraction >= 0.5) return whole + 1.0;
  if (fraction <= -0.5) return whole - 1.0;
  return whole;
}

}  // namespace

HexCell RoundCube(const Eigen::Vector3d& u) {
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

Eigen::Matrix3d CubeRotation(double psi) {
  const double c = std::cos(psi);
  const double s = std::sin(psi);
  const double diag = 2.0 * c + 1.0;
  const double plus = 1.0 - c + kSqrt3 * s;
  const double minus = 1.0 - c - kSqrt3 * s;
  Eigen::Matrix3d r;
  r << diag, minus, plus,
       plus, diag, minus,
       minus, plus, diag;
  return r / 3.0;
}

Eigen::Vector3d CubeRotationDerivative(const Eigen::Vector3d& s, double psi) {
  const double sn = std::sin(psi);
  const double cs = std::cos(psi) / kSqrt3;
  return {-s.x() * sn + (s.z() - s.y()) * cs,
          -s.y() * sn + (s.x() - s.z()) * cs,
          -s.z() * sn + (s.y() - s.x()) * cs};
}

}  // namespace hex_slam
