#include "hex_slam/geometry/ray_traversal.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

std::pair<int, int> Key(const HexCell& c) { return {c.a, c.b}; }
std::pair<int, int> Key(const GridIndex& c) { return {c.col, c.row}; }

bool AreNeighbours(const HexCell& x, const HexCell& y) {
  const int da = y.a - x.a, db = y.b - x.b, dc = y.c() - x.c();
  return std::max({std::abs(da), std::abs(db), std::abs(dc)}) == 1;
}
bool AreNeighbours(const GridIndex& x, const GridIndex& y) {
  return std::abs(x.col - y.col) + std::abs(x.row - y.row) == 1;
}

// Distance from point p to segment ab.
double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::max(0.0, std::min(1.0, (p - a).dot(ab) / ab.squaredNorm()));
  return (a + t * ab - p).norm();
}

// Traversal against dense sampling: every sampled cell before the endpoint cell is crossed;
// every crossed cell is sampled or (a clipped corner too thin to sample) touches the segment;
// no repeats; consecutive cells share an edge; the endpoint cell is never among the crossed.
template <class Lattice>
void CheckAgainstDenseSampling(const Lattice& lattice, double circumradius, unsigned seed,
                               int trials) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<typename Lattice::Cell> crossed;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Vector2d a(u(rng), u(rng));
    Eigen::Vector2d b(u(rng), u(rng));
    if (trial % 10 == 0) b = a + Eigen::Vector2d(u(rng), 0.0);  // axis-aligned rays too
    if (trial % 10 == 1) b = a + Eigen::Vector2d(0.0, u(rng));
    if (trial % 10 == 2) {
      // Along a multiple of 30°: parallel to a hexagon's sides or through its vertices, where a
      // forward side is never crossed and exits tie.
      const double angle = (M_PI / 6.0) * static_cast<int>(trial / 10 % 12);
      b = a + u(rng) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    }
    TraceRay(lattice, a, b, &crossed);
    const auto end = lattice.CellOf(b);
    std::set<std::pair<int, int>> crossed_set;
    for (std::size_t i = 0; i < crossed.size(); ++i) {
      ASSERT_TRUE(crossed_set.insert(Key(crossed[i])).second) << "cell visited twice";
      ASSERT_NE(Key(crossed[i]), Key(end)) << "endpoint cell returned as free";
      if (i > 0) {
        ASSERT_TRUE(AreNeighbours(crossed[i - 1], crossed[i]));
      }
    }
    if (!crossed.empty()) {
      EXPECT_EQ(Key(crossed.front()), Key(lattice.CellOf(a)));
      EXPECT_TRUE(AreNeighbours(crossed.back(), end));
    }
    const double length = (b - a).norm();
    const int samples = 2 + static_cast<int>(length / lattice.spacing() * 2000);
    std::set<std::pair<int, int>> sampled;
    for (int k = 0; k <= samples; ++k) {
      const auto cell = lattice.CellOf(a + (b - a) * (static_cast<double>(k) / samples));
      if (Key(cell) != Key(end)) sampled.insert(Key(cell));
    }
    for (const auto& key : sampled) {
      EXPECT_TRUE(crossed_set.count(key)) << "sampled cell missed by traversal";
    }
    for (const auto& cell : crossed) {
      if (sampled.count(Key(cell))) continue;
      EXPECT_LE(SegmentDistance(lattice.CentreOf(cell), a, b), circumradius + 1e-9);
    }
  }
}

TEST(RayTraversalTest, HexMatchesDenseSampling) {
  const HexLattice lattice(0.137);
  CheckAgainstDenseSampling(lattice, lattice.spacing() / kSqrt3, 1, 1500);
}

TEST(RayTraversalTest, SquareMatchesDenseSampling) {
  const SquareLattice lattice(0.137);
  CheckAgainstDenseSampling(lattice, lattice.spacing() / std::sqrt(2.0), 2, 1500);
}

TEST(RayTraversalTest, RayWithinOneCellCrossesNothing) {
  const HexLattice lattice(1.0);
  std::vector<HexCell> crossed;
  TraceRay(lattice, {0.01, 0.02}, {0.1, -0.1}, &crossed);
  EXPECT_TRUE(crossed.empty());
}

TEST(RayTraversalTest, RayThroughLatticeVerticesStillWalksNeighbours) {
  // Along 0° a hex ray runs through vertices where three cells meet: the walk must stay
  // connected and finish next to the endpoint.
  const HexLattice lattice(1.0);
  std::vector<HexCell> crossed;
  TraceRay(lattice, {0.0, 0.5}, {20.0, 0.5}, &crossed);
  ASSERT_GT(crossed.size(), 10u);
  for (std::size_t i = 1; i < crossed.size(); ++i) {
    EXPECT_TRUE(AreNeighbours(crossed[i - 1], crossed[i]));
  }
  EXPECT_TRUE(AreNeighbours(crossed.back(), lattice.CellOf({20.0, 0.5})));
}

}  // namespace
}  // namespace hex_slam
