// Cube coordinates (MATH.md §1, §3, §5): three axes 120° apart, x + y + ζ = 0.
//
// Cartesian (X, Y) maps to its projections on the axes at 0°, 120° and 240°. A cube-space tangent
// vector is sqrt(1.5) times longer than its Cartesian image, so cube norms are never metres.
#ifndef HEX_SLAM_GEOMETRY_CUBE_H_
#define HEX_SLAM_GEOMETRY_CUBE_H_

#include <Eigen/Core>

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

// Paper Algorithm 1: the lattice point nearest to `u` (lattice units, u.x+u.y+u.z = 0). The
// coordinate whose rounding moved furthest is the one recomputed from the other two.
HexCell RoundCube(const Eigen::Vector3d& u);

// Rotation by psi about (1,1,1)/sqrt(3); counter-clockwise in Cartesian terms (paper eq. 10).
Eigen::Matrix3d CubeRotation(double psi);

// d/dpsi of CubeRotation(psi) * s, written out as MATH.md §5 gives it.
Eigen::Vector3d CubeRotationDerivative(const Eigen::Vector3d& s, double psi);

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_CUBE_H_
