// MarkGrazingEndpoints against the incidence computed from the geometry the points were made on.
#include "hex_slam/sensor/grazing_endpoints.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

double Radians(double degrees) { return degrees * M_PI / 180.0; }

Eigen::Vector2d Beam(double degrees, double range) {
  return range * Eigen::Vector2d(std::cos(Radians(degrees)), std::sin(Radians(degrees)));
}

// A straight wall at y = 1 seen from the origin, beams at 2.5°, 3.5°, ..., 177.5°: the beam at
// angle φ meets the wall |90° - φ| from its normal.
TEST(GrazingEndpointsTest, AStraightWallIsMarkedExactlyWhereTheIncidenceExceedsTheLimit) {
  std::vector<double> angles;
  std::vector<Eigen::Vector2d> points;
  for (double phi = 2.5; phi < 178.0; phi += 1.0) {
    angles.push_back(phi);
    points.push_back(Beam(phi, 1.0 / std::sin(Radians(phi))));
  }
  for (const double limit : {60.0, 75.0, 80.0, 85.0}) {
    std::vector<bool> grazing;
    const int returned = MarkGrazingEndpoints(points, Radians(limit), &grazing);
    ASSERT_EQ(grazing.size(), points.size());
    int marked = 0;
    for (std::size_t i = 1; i + 1 < points.size(); ++i) {
      const bool expected = std::abs(90.0 - angles[i]) > limit;
      EXPECT_EQ(grazing[i], expected) << "beam at " << angles[i] << "°, limit " << limit << "°";
      marked += grazing[i];
    }
    EXPECT_GT(marked, 0) << limit;
    EXPECT_EQ(returned, marked) << limit;
    // The scan's ends have a neighbour on one side only.
    EXPECT_FALSE(grazing.front());
    EXPECT_FALSE(grazing.back());
  }
}

TEST(GrazingEndpointsTest, ADepthJumpIsNotGrazingThoughItsChordRunsAlongTheBeam) {
  // Beams 1° apart: a near wall 2 m off, then a far one at 6 m; the middle point's chord runs
  // almost along its beam, but its gaps are 0.035 m and 4 m.
  const std::vector<Eigen::Vector2d> points = {Beam(0.0, 2.0), Beam(1.0, 2.0), Beam(2.0, 6.0)};
  std::vector<bool> grazing;
  MarkGrazingEndpoints(points, Radians(80.0), &grazing);
  EXPECT_EQ(grazing, std::vector<bool>({false, false, false}));
  // Three points on one straight wall (x = 2) at the same beam angles are a straight stretch:
  // with a limit of 0.5° the middle one, met 1° from the normal, is marked, so the jump above
  // was left unmarked for its gaps and not for its angle.
  const std::vector<Eigen::Vector2d> straight = {
      Beam(0.0, 2.0), Beam(1.0, 2.0 / std::cos(Radians(1.0))),
      Beam(2.0, 2.0 / std::cos(Radians(2.0)))};
  MarkGrazingEndpoints(straight, Radians(0.5), &grazing);
  EXPECT_EQ(grazing, std::vector<bool>({false, true, false}));
  MarkGrazingEndpoints(points, Radians(0.5), &grazing);
  EXPECT_EQ(grazing, std::vector<bool>({false, false, false}));
}

TEST(GrazingEndpointsTest, ACornerIsNotAStraightStretch) {
  // Three points 0.2 m apart along y = 1, bent at the middle by a 1 m step towards the sensor:
  // the middle point lies far off its neighbours' chord.
  const std::vector<Eigen::Vector2d> points = {{5.0, 1.0}, {5.2, 0.0}, {5.4, 1.0}};
  std::vector<bool> grazing;
  MarkGrazingEndpoints(points, Radians(10.0), &grazing);
  EXPECT_EQ(grazing, std::vector<bool>({false, false, false}));
}

TEST(GrazingEndpointsTest, ARightAngleLimitMarksNothing) {
  std::vector<Eigen::Vector2d> points;
  for (double phi = 0.5; phi < 10.0; phi += 1.0) points.push_back(Beam(phi, 1.0 / std::sin(Radians(phi))));
  std::vector<bool> grazing;
  MarkGrazingEndpoints(points, 0.5 * M_PI, &grazing);
  EXPECT_EQ(grazing, std::vector<bool>(points.size(), false));
  MarkGrazingEndpoints({}, Radians(80.0), &grazing);
  EXPECT_TRUE(grazing.empty());
  MarkGrazingEndpoints({{1.0, 0.0}, {0.0, 1.0}}, Radians(1.0), &grazing);
  EXPECT_EQ(grazing, std::vector<bool>({false, false}));
}

}  // namespace
}  // namespace hex_slam
