#include "hex_slam/geometry/hex_lattice.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace {

TEST(HexLatticeTest, NeighboursAreSpacingApartAtTheSixFlatTopAngles) {
  const HexLattice lattice(0.1);
  const HexCell centre{3, -7};
  const Eigen::Vector2d c = lattice.CentreOf(centre);
  const int da[6] = {1, 1, 0, -1, -1, 0}, db[6] = {-1, 0, 1, 1, 0, -1};
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector2d n = lattice.CentreOf(HexCell{centre.a + da[k], centre.b + db[k]});
    EXPECT_NEAR((n - c).norm(), 0.1, 1e-12);
    EXPECT_NEAR(std::atan2(n.y() - c.y(), n.x() - c.x()) * 180.0 / M_PI,
                std::remainder(-30.0 + 60.0 * k, 360.0), 1e-9);
  }
}

TEST(HexLatticeTest, CellOfCentreIsTheCell) {
  const HexLattice lattice(0.0537);
  for (int a = -40; a <= 40; a += 3) {
    for (int b = -40; b <= 40; b += 7) {
      EXPECT_EQ(lattice.CellOf(lattice.CentreOf(HexCell{a, b})), (HexCell{a, b}));
    }
  }
}

TEST(HexLatticeTest, CellAreaAndEqualAreaSpacing) {
  // MATH.md §2: 0.01 m² → d ≈ 0.1075 m; 0.04 m² → d ≈ 0.2149 m.
  EXPECT_NEAR(HexLattice::SpacingForArea(0.01), 0.10746, 1e-4);
  EXPECT_NEAR(HexLattice::SpacingForArea(0.04), 0.21491, 1e-4);
  EXPECT_NEAR(HexLattice(HexLattice::SpacingForArea(0.01)).cell_area(), 0.01, 1e-12);
}

TEST(HexLatticeTest, CellAreaMatchesMonteCarloCount) {
  // Count random points per cell: every cell should get area-proportional share.
  const HexLattice lattice(0.5);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  const int n = 200000;
  int in_origin_cell = 0;
  const HexCell target = lattice.CellOf({5.0, 5.0});
  for (int i = 0; i < n; ++i) in_origin_cell += lattice.CellOf({u(rng), u(rng)}) == target;
  const double area = 100.0 * in_origin_cell / n;
  EXPECT_NEAR(area, lattice.cell_area(), 0.05 * lattice.cell_area());
}

TEST(HexLatticeTest, StorageIndexRoundTripsAndIsDenseOverARectangle) {
  for (int a = -9; a <= 9; ++a) {
    for (int b = -9; b <= 9; ++b) {
      const HexCell c{a, b};
      EXPECT_EQ(HexLattice::FromIndex(HexLattice::ToIndex(c)), c);
    }
  }
  // Odd-q: consecutive rows in one column are d apart vertically, columns w apart horizontally.
  const HexLattice lattice(1.0);
  for (int col = -3; col <= 3; ++col) {
    const Eigen::Vector2d p0 = lattice.CentreOf(GridIndex{col, 0});
    const Eigen::Vector2d p1 = lattice.CentreOf(GridIndex{col, 1});
    EXPECT_NEAR(p1.y() - p0.y(), 1.0, 1e-12);
    EXPECT_NEAR(p0.x(), col * lattice.cube_scale(), 1e-12);
    EXPECT_GE(p0.y(), 0.0);
    EXPECT_LT(p0.y(), 1.0);
  }
}

template <class Lattice>
void ExpectIndexBoundsCover(const Lattice& lattice) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const Eigen::AlignedBox2d box(Eigen::Vector2d(-1.3, -0.7), Eigen::Vector2d(2.1, 1.9));
  GridIndex lo, hi;
  lattice.IndexBounds(box, &lo, &hi);
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    if (!box.contains(p)) continue;
    const GridIndex index = Lattice::ToIndex(lattice.CellOf(p));
    EXPECT_GE(index.col, lo.col);
    EXPECT_LE(index.col, hi.col);
    EXPECT_GE(index.row, lo.row);
    EXPECT_LE(index.row, hi.row);
  }
}

TEST(HexLatticeTest, IndexBoundsCoverTheBox) { ExpectIndexBoundsCover(HexLattice(0.13)); }
TEST(SquareLatticeTest, IndexBoundsCoverTheBox) { ExpectIndexBoundsCover(SquareLattice(0.13)); }

TEST(HexLatticeTest, StencilWeightsReproduceThePointAndPickTheNearestCentres) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p = CartesianToCube(u(rng), u(rng));
    const HexStencil st = HexLattice::Stencil(p);
    Eigen::Vector3d reproduced = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(st.weights[k], -1e-12);
      EXPECT_LE(st.weights[k], 1.0 + 1e-12);
      total += st.weights[k];
      const HexCell& c = st.cells[k];
      reproduced += st.weights[k] * Eigen::Vector3d(c.a, c.b, c.c());
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
    EXPECT_NEAR((reproduced - p).norm(), 0.0, 1e-9);
    // The three stencil cells are the three nearest lattice points (the Delaunay triangle).
    const Eigen::Vector2d q = CubeToCartesian(p);
    double worst_stencil = 0.0;
    for (const HexCell& c : st.cells) {
      worst_stencil = std::max(worst_stencil,
                               (CubeToCartesian(Eigen::Vector3d(c.a, c.b, c.c())) - q).norm());
    }
    int closer = 0;
    const HexCell nearest = RoundCube(p);
    for (int a = nearest.a - 2; a <= nearest.a + 2; ++a) {
      for (int b = nearest.b - 2; b <= nearest.b + 2; ++b) {
        closer += (CubeToCartesian(Eigen::Vector3d(a, b, -a - b)) - q).norm() <
                  worst_stencil - 1e-9;
      }
    }
    EXPECT_LE(closer, 2);
  }
}

}  // namespace
}  // namespace hex_slam
