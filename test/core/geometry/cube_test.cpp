#include "hex_slam/geometry/cube.h"

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

namespace hex_slam {
namespace {

TEST(CubeTest, CartesianRoundTripAndPlaneInvariant) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const CubePoint c = CubePoint::FromCartesian(p);
    EXPECT_NEAR(c.x() + c.y() + c.z(), 0.0, 1e-12);
    EXPECT_NEAR((c.ToCartesian() - p).norm(), 0.0, 1e-12);
  }
}

TEST(CubeTest, PolarEqualsCartesianOfTheSameReturn) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> range(0.0, 30.0), bearing(-M_PI, M_PI);
  for (int i = 0; i < 1000; ++i) {
    const double r = range(rng), phi = bearing(rng);
    const CubePoint polar = CubePoint::FromPolar(r, phi);
    const CubePoint cart = CubePoint::FromCartesian({r * std::cos(phi), r * std::sin(phi)});
    EXPECT_NEAR((polar.vector() - cart.vector()).norm(), 0.0, 1e-12);
  }
}

TEST(CubeTest, TangentNormIsSqrtOnePointFiveTimesCartesian) {
  // MATH.md §1: cube-space lengths are not metres.
  const Eigen::Vector3d v = CartesianToCube(3.0, 4.0);
  EXPECT_NEAR(v.squaredNorm(), 1.5 * 25.0, 1e-12);
}

TEST(CubeTest, FromComponentsRejectsPointsOffThePlane) {
  EXPECT_NO_THROW(CubePoint::FromComponents(1.0, -0.5, -0.5));
  EXPECT_THROW(CubePoint::FromComponents(1.0, 0.0, 0.0), std::invalid_argument);
}

TEST(CubeTest, RoundingEqualsBruteForceNearestCentre) {
  // Paper Algorithm 1 against the nearest of all lattice points in a neighbourhood, measured in
  // Cartesian distance, on 20000 random points.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  int ties = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const Eigen::Vector3d lattice_units = CartesianToCube(p.x(), p.y());
    const HexCell rounded = RoundCube(lattice_units);
    const int a0 = static_cast<int>(std::floor(lattice_units.x()));
    const int b0 = static_cast<int>(std::floor(lattice_units.y()));
    double best = 1e9, second = 1e9;
    HexCell nearest;
    for (int a = a0 - 3; a <= a0 + 3; ++a) {
      for (int b = b0 - 3; b <= b0 + 3; ++b) {
        const Eigen::Vector2d centre = CubeToCartesian(Eigen::Vector3d(a, b, -a - b));
        const double dist = (centre - p).norm();
        if (dist < best) {
          second = best;
          best = dist;
          nearest = HexCell{a, b};
        } else if (dist < second) {
          second = dist;
        }
      }
    }
    if (second - best < 1e-9) {
      ++ties;
      continue;
    }
    ASSERT_EQ(rounded, nearest) << "point " << p.transpose();
  }
  EXPECT_LT(ties, 5);
}

TEST(CubeTest, RoundingIsIdentityOnLatticePoints) {
  for (int a = -5; a <= 5; ++a) {
    for (int b = -5; b <= 5; ++b) {
      EXPECT_EQ(RoundCube(Eigen::Vector3d(a, b, -a - b)), (HexCell{a, b}));
    }
  }
}

// The paper's rounding, written with the library's std::round (halves away from zero).
HexCell LibraryRoundCube(const Eigen::Vector3d& u) {
  double rx = std::round(u.x()), ry = std::round(u.y()), rz = std::round(u.z());
  const double dx = std::abs(rx - u.x()), dy = std::abs(ry - u.y()), dz = std::abs(rz - u.z());
  if (dx > dy && dx > dz) {
    rx = -ry - rz;
  } else if (dy > dz) {
    ry = -rx - rz;
  }
  return HexCell{static_cast<int>(rx), static_cast<int>(ry)};
}

TEST(CubeTest, RoundingAgreesWithTheLibraryRoundOnTiesAndNearTies) {
  // Halves, the doubles either side of them, and random points, positive and negative.
  std::vector<double> values;
  for (int k = -6; k <= 6; ++k) {
    const double half = k + 0.5;
    values.insert(values.end(), {half, std::nextafter(half, -1e9), std::nextafter(half, 1e9),
                                 static_cast<double>(k), 0.49999999999999994 + k});
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int i = 0; i < 2000; ++i) values.push_back(u(rng));
  for (double a : values) {
    for (double b : {0.5, -0.5, 0.25, -1e-300, 3.0}) {
      const Eigen::Vector3d cube(a, b, -a - b);
      ASSERT_EQ(RoundCube(cube), LibraryRoundCube(cube)) << "cube " << cube.transpose();
    }
  }
}

TEST(CubeTest, RotationEqualsCartesianRotation) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-10.0, 10.0), angle(-M_PI, M_PI);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const double psi = angle(rng);
    const Eigen::Vector2d rotated(std::cos(psi) * p.x() - std::sin(psi) * p.y(),
                                  std::sin(psi) * p.x() + std::cos(psi) * p.y());
    const Eigen::Vector3d cube_rotated = CubeRotation(psi) * CartesianToCube(p.x(), p.y());
    EXPECT_NEAR((cube_rotated - CartesianToCube(rotated.x(), rotated.y())).norm(), 0.0, 1e-12);
  }
}

TEST(CubeTest, RotationIsOrthogonalAndFixesTheAxis) {
  const Eigen::Matrix3d r = CubeRotation(0.7);
  EXPECT_NEAR((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((r * Eigen::Vector3d::Ones() - Eigen::Vector3d::Ones()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
}

TEST(CubeTest, RotationDerivativeEqualsFiniteDifference) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-10.0, 10.0), angle(-M_PI, M_PI);
  const double h = 1e-6;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d s = CartesianToCube(u(rng), u(rng));
    const double psi = angle(rng);
    const Eigen::Vector3d fd = (CubeRotation(psi + h) * s - CubeRotation(psi - h) * s) / (2 * h);
    EXPECT_NEAR((CubeRotationDerivative(s, psi) - fd).norm(), 0.0, 1e-6 * (1.0 + s.norm()));
  }
}

}  // namespace
}  // namespace hex_slam
