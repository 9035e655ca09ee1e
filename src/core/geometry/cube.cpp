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
