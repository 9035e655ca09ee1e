#include "hex_slam/map/hex_interpolation.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/map/bilinear_interpolation.h"

namespace hex_slam {
namespace {

constexpr double kSpacing = 0.2;

// A grid over [-3, 3]² with random log-odds in every cell.
template <class Lattice>
GridMap<Lattice> RandomGrid(unsigned seed) {
  const OccupancyModel model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  GridMap<Lattice> grid(Lattice(kSpacing), model, GridGrowthPolicy(),
                        Eigen::AlignedBox2d(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3)));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  std::vector<float> values(grid.rect().size());
  for (float& v : values) v = u(rng);
  grid.Assign(grid.rect(), values);
  return grid;
}

// True if the point is at least `margin` (lattice units) from every triangle edge, where the
// interpolant has a kink and finite differences straddle two planes.
bool AwayFromTriangleEdges(const Eigen::Vector3d& cube_point, double margin) {
  const Eigen::Vector3d u = cube_point / (0.5 * kSqrt3 * kSpacing);
  for (int k = 0; k < 3; ++k) {
    const double frac = u[k] - std::floor(u[k]);
    if (frac < margin || frac > 1.0 - margin) return false;
  }
  return true;
}

TEST(HexInterpolationTest, ReproducesCentreValues) {
  const HexGrid grid = RandomGrid<HexLattice>(1);
  for (int a = -8; a <= 8; ++a) {
    for (int b = -8; b <= 8; ++b) {
      const HexCell cell{a, b};
      const Eigen::Vector2d c = grid.lattice().CentreOf(cell);
      const HexSample s = InterpolateHex(grid, CartesianToCube(c.x(), c.y()));
      EXPECT_NEAR(s.value, grid.Probability(cell), 1e-6);
    }
  }
}

TEST(HexInterpolationTest, IsContinuousAcrossTriangleEdges) {
  const HexGrid grid = RandomGrid<HexLattice>(2);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0), angle(0, 2 * M_PI);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const double t = angle(rng);
    const Eigen::Vector2d q = p + 1e-9 * Eigen::Vector2d(std::cos(t), std::sin(t));
    EXPECT_NEAR(InterpolateHex(grid, CartesianToCube(p.x(), p.y())).value,
                InterpolateHex(grid, CartesianToCube(q.x(), q.y())).value, 1e-7);
  }
}

TEST(HexInterpolationTest, GradientEqualsFiniteDifferencesAndLiesInThePlane) {
  const HexGrid grid = RandomGrid<HexLattice>(4);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0), angle(0, 2 * M_PI);
  const double h = 1e-7;
  int tested = 0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const Eigen::Vector3d cp = CartesianToCube(p.x(), p.y());
    if (!AwayFromTriangleEdges(cp, 1e-4)) continue;
    ++tested;
    const HexSample s = InterpolateHex(grid, cp);
    EXPECT_NEAR(s.gradient.sum(), 0.0, 1e-9);
    const double t = angle(rng);
    const Eigen::Vector2d e(std::cos(t), std::sin(t));
    const Eigen::Vector2d a = p + h * e, b = p - h * e;
    const double fd = (InterpolateHex(grid, CartesianToCube(a.x(), a.y())).value -
                       InterpolateHex(grid, CartesianToCube(b.x(), b.y())).value) /
                      (2 * h);
    // Directional derivative = gradient · (the direction's cube-space image).
    const double analytic = s.gradient.dot(CartesianToCube(e.x(), e.y()));
    EXPECT_NEAR(analytic, fd, 1e-5 * (1.0 + std::abs(fd)));
  }
  EXPECT_GT(tested, 4000);
}

TEST(HexInterpolationTest, PapersPerAxisPartialsOverstateDerivativesByThreeHalves) {
  // MATH.md §4: the paper's partials are derivatives along each axis direction. Measured by finite
  // differences along the three axes (0°, 120°, 240°) and used as a gradient, they predict every
  // directional derivative 1.5 times too large.
  const HexGrid grid = RandomGrid<HexLattice>(6);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0), angle(0, 2 * M_PI);
  const double h = 1e-7;
  auto value = [&grid](const Eigen::Vector2d& q) {
    return InterpolateHex(grid, CartesianToCube(q.x(), q.y())).value;
  };
  int tested = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    if (!AwayFromTriangleEdges(CartesianToCube(p.x(), p.y()), 1e-4)) continue;
    Eigen::Vector3d per_axis;
    for (int k = 0; k < 3; ++k) {
      const double phi = 2.0 * M_PI * k / 3.0;
      const Eigen::Vector2d axis(std::cos(phi), std::sin(phi));
      per_axis[k] = (value(p + h * axis) - value(p - h * axis)) / (2 * h);
    }
    const double t = angle(rng);
    const Eigen::Vector2d e(std::cos(t), std::sin(t));
    const double true_derivative = (value(p + h * e) - value(p - h * e)) / (2 * h);
    if (std::abs(true_derivative) < 1e-2) continue;
    ++tested;
    EXPECT_NEAR(per_axis.dot(CartesianToCube(e.x(), e.y())) / true_derivative, 1.5, 1e-4);
  }
  EXPECT_GT(tested, 1000);
}

TEST(BilinearInterpolationTest, ReproducesCentreValuesAndGradientEqualsFiniteDifferences) {
  const SquareGrid grid = RandomGrid<SquareLattice>(8);
  for (int i = -8; i <= 8; ++i) {
    for (int j = -8; j <= 8; ++j) {
      const SquareSample s = InterpolateBilinear(grid, grid.lattice().CentreOf(GridIndex{i, j}));
      EXPECT_NEAR(s.value, grid.ProbabilityAt({i, j}), 1e-6);
    }
  }
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const double h = 1e-7;
  for (int n = 0; n < 2000; ++n) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const Eigen::Vector2d cell_units = p / kSpacing;
    const Eigen::Vector2d frac = cell_units - cell_units.array().floor().matrix();
    if ((frac.array() < 1e-4).any() || (frac.array() > 1 - 1e-4).any()) continue;
    const SquareSample s = InterpolateBilinear(grid, p);
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector2d e = Eigen::Vector2d::Unit(axis) * h;
      const double fd =
          (InterpolateBilinear(grid, p + e).value - InterpolateBilinear(grid, p - e).value) /
          (2 * h);
      EXPECT_NEAR(s.gradient[axis], fd, 1e-5 * (1.0 + std::abs(fd)));
    }
  }
}

// A straight wall at x = `wall_x` seen from the left, mapped by a fan of beams.
template <class Lattice>
GridMap<Lattice> WallGrid(double spacing, double wall_x) {
  const OccupancyModel model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  GridMap<Lattice> grid(Lattice(spacing), model, GridGrowthPolicy(),
                        Eigen::AlignedBox2d(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3)));
  std::vector<Eigen::Vector2d> ends;
  for (double y = -1.5; y <= 1.5; y += 0.01) ends.emplace_back(wall_x, y);
  for (int repeat = 0; repeat < 3; ++repeat) grid.InsertScan({wall_x - 1.5, 0.0}, ends);
  return grid;
}

// Where along y = `y` the interpolated occupancy peaks near the wall, sampled every 0.1 mm.
template <class F>
double PeakX(double from, double to, double y, F value) {
  double best_x = from, best = -1.0;
  for (double x = from; x <= to; x += 1e-4) {
    const double v = value(Eigen::Vector2d(x, y));
    if (v > best) best = v, best_x = x;
  }
  return best_x;
}

TEST(HexInterpolationTest, SubcellOccupancyPeaksOnTheWallNotAtTheCellCentres) {
  const double d = 0.2, wall_x = 0.37;  // the wall well inside its cells, not on a centre
  const HexGrid grid = WallGrid<HexLattice>(d, wall_x);
  for (double y : {-0.33, 0.0, 0.21, 0.5}) {
    const double plain = PeakX(wall_x - d, wall_x + d, y, [&](const Eigen::Vector2d& p) {
      return InterpolateHex(grid, CartesianToCube(p.x(), p.y())).value;
    });
    const double subcell = PeakX(wall_x - d, wall_x + d, y, [&](const Eigen::Vector2d& p) {
      return InterpolateHexSubcell(grid, CartesianToCube(p.x(), p.y())).value;
    });
    EXPECT_GT(std::abs(plain - wall_x), 0.01) << "y " << y << ": the plain map's peak is biased";
    EXPECT_NEAR(subcell, wall_x, 0.003) << "y " << y;
  }
}

TEST(BilinearInterpolationTest, SubcellOccupancyPeaksOnTheWallNotAtTheCellCentres) {
  const double s = 0.2, wall_x = 0.37;
  const SquareGrid grid = WallGrid<SquareLattice>(s, wall_x);
  for (double y : {-0.33, 0.0, 0.21, 0.5}) {
    const double plain = PeakX(wall_x - s, wall_x + s, y, [&](const Eigen::Vector2d& p) {
      return InterpolateBilinear(grid, p).value;
    });
    const double subcell = PeakX(wall_x - s, wall_x + s, y, [&](const Eigen::Vector2d& p) {
      return InterpolateBilinearSubcell(grid, p).value;
    });
    EXPECT_NEAR(plain, 0.4, 1e-3) << "y " << y << ": the plain map peaks at the cell centre";
    EXPECT_NEAR(subcell, wall_x, 0.003) << "y " << y;
  }
}

TEST(HexInterpolationTest, SubcellEqualsPlainWhereNothingWasHit) {
  // Maps assigned from files carry no hits: the sub-cell reading is the plain one.
  const HexGrid hex = RandomGrid<HexLattice>(11);
  const SquareGrid square = RandomGrid<SquareLattice>(12);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const Eigen::Vector3d c = CartesianToCube(p.x(), p.y());
    EXPECT_EQ(InterpolateHexSubcell(hex, c).value, InterpolateHex(hex, c).value);
    EXPECT_EQ(InterpolateBilinearSubcell(square, p).value, InterpolateBilinear(square, p).value);
  }
}

// A map of scattered hits: random endpoints around the origin, so stencils mix hit, freed and
// unknown cells with offsets anywhere in their cells.
template <class Lattice>
GridMap<Lattice> ScatteredHitsGrid(unsigned seed) {
  const OccupancyModel model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  GridMap<Lattice> grid(Lattice(kSpacing), model, GridGrowthPolicy(),
                        Eigen::AlignedBox2d(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3)));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (int scan = 0; scan < 20; ++scan) {
    std::vector<Eigen::Vector2d> ends(150);
    for (Eigen::Vector2d& e : ends) e = Eigen::Vector2d(u(rng), u(rng));
    grid.InsertScan(Eigen::Vector2d(0.2 * u(rng), 0.2 * u(rng)), ends);
  }
  return grid;
}

TEST(HexInterpolationTest, HitOffsetIsTheStencilsMeanHitOffset) {
  // The definition the matcher's blended records must keep: the mean of the three nearest
  // centres' hit offsets (HexLattice::Stencil), weighted by interpolation weight times occupancy.
  const HexGrid grid = ScatteredHitsGrid<HexLattice>(14);
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> u(-2.7, 2.7);  // inside storage: Stencil's cells exist
  const double inv_w = grid.lattice().inv_cube_scale();
  int moved = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d at = CartesianToCube(u(rng), u(rng)) * inv_w;
    const double ux = at.x(), uy = at.y();
    const HexStencil st = HexLattice::Stencil(Eigen::Vector3d(ux, uy, -ux - uy));
    std::size_t cells[3];
    for (int k = 0; k < 3; ++k) cells[k] = grid.rect().Offset(HexLattice::ToIndex(st.cells[k]));
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();  // metres, world axes
    const bool hit = MeanHitOffset(grid.hit_records(), grid.hit_slots(), cells, st.weights, 3, &mean);
    const Eigen::Vector3d expected = CartesianToCube(mean.x(), mean.y()) * inv_w;
    double ox, oy;
    HexHitOffset(grid, ux, uy, &ox, &oy);
    moved += hit;
    // The records are summed in float lanes: equal to a micrometre.
    const double w = grid.lattice().cube_scale();
    ASSERT_NEAR(ox * w, expected.x() * w, 1e-6) << ux << " " << uy;
    ASSERT_NEAR(oy * w, expected.y() * w, 1e-6) << ux << " " << uy;
  }
  EXPECT_GT(moved, 5000);
}

// The same scans in storage that ends right at the cells they wrote and in storage with room to
// spare: every reading, sub-cell offsets included, is the same, so nothing that reads the map
// depends on where its storage happens to end (a submap grown early, or late).
template <class Lattice, class Read>
void ExpectReadingsIndependentOfTheStorage(unsigned seed, Read read) {
  const OccupancyModel model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  GridGrowthPolicy fixed;
  fixed.auto_grow = false;
  const Eigen::Vector2d corner(2.5, 2.5);
  GridMap<Lattice> tight(Lattice(kSpacing), model, fixed, Eigen::AlignedBox2d(-corner, corner));
  GridMap<Lattice> roomy(Lattice(kSpacing), model, fixed,
                         Eigen::AlignedBox2d(-2.0 * corner, 2.0 * corner));
  std::mt19937_64 rng(seed);
  // Endpoints up to the tight storage's outermost cells.
  const Eigen::AlignedBox2d storage = tight.StorageExtent();
  std::uniform_real_distribution<double> ux(storage.min().x(), storage.max().x());
  std::uniform_real_distribution<double> uy(storage.min().y(), storage.max().y());
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (int scan = 0; scan < 20; ++scan) {
    std::vector<Eigen::Vector2d> ends(150);
    for (Eigen::Vector2d& e : ends) e = Eigen::Vector2d(ux(rng), uy(rng));
    const Eigen::Vector2d origin(0.2 * u(rng), 0.2 * u(rng));
    tight.InsertScan(origin, ends);
    roomy.InsertScan(origin, ends);
  }
  ASSERT_EQ(tight.points_outside(), 0);
  std::uniform_real_distribution<double> near_edge(2.4, 3.0);
  int differs_from_plain = 0;
  for (int i = 0; i < 20000; ++i) {
    // Points near the tight storage's edge, on all four sides.
    Eigen::Vector2d p(near_edge(rng), u(rng));
    if (i % 2) std::swap(p.x(), p.y());
    if (i % 4 >= 2) p = -p;
    const auto a = read(tight, p, true), b = read(roomy, p, true);
    ASSERT_EQ(a.value, b.value) << p.transpose();
    ASSERT_EQ(a.gradient, b.gradient) << p.transpose();
    differs_from_plain += a.value != read(tight, p, false).value;
  }
  EXPECT_GT(differs_from_plain, 1000);  // the offsets were there to read
}

TEST(HexInterpolationTest, SubcellReadingsDoNotDependOnWhereTheStorageEnds) {
  ExpectReadingsIndependentOfTheStorage<HexLattice>(
      18, [](const HexGrid& grid, const Eigen::Vector2d& p, bool subcell) {
        const Eigen::Vector3d c = CartesianToCube(p.x(), p.y());
        return subcell ? InterpolateHexSubcell(grid, c) : InterpolateHex(grid, c);
      });
}

TEST(BilinearInterpolationTest, SubcellReadingsDoNotDependOnWhereTheStorageEnds) {
  ExpectReadingsIndependentOfTheStorage<SquareLattice>(
      19, [](const SquareGrid& grid, const Eigen::Vector2d& p, bool subcell) {
        return subcell ? InterpolateBilinearSubcell(grid, p) : InterpolateBilinear(grid, p);
      });
}

TEST(HexInterpolationTest, PartialsAreTheInPlaneGradientsComponents) {
  // d_x = g_x - g_ζ, d_y = g_y - g_ζ for the in-plane gradient g; and both reproduce the value.
  const HexGrid grid = RandomGrid<HexLattice>(16);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-2.5, 2.5);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d at = CartesianToCube(u(rng), u(rng)) * grid.lattice().inv_cube_scale();
    const double ux = at.x(), uy = at.y();
    const HexPartials p = InterpolateHexPartials(grid, ux, uy);
    const HexStencil st = HexLattice::Stencil(Eigen::Vector3d(ux, uy, -ux - uy));
    double value = 0.0;
    for (int k = 0; k < 3; ++k) value += st.weights[k] * grid.Probability(st.cells[k]);
    EXPECT_NEAR(p.value, value, 1e-12);
    const HexSample s = InterpolateHexLatticeUnits(grid, ux, uy);
    EXPECT_NEAR(p.du_x, s.gradient.x() - s.gradient.z(), 1e-12);
    EXPECT_NEAR(p.du_y, s.gradient.y() - s.gradient.z(), 1e-12);
  }
}

TEST(HexInterpolationTest, OutsideTheMapReadsUnknownWithZeroGradient) {
  const HexGrid grid = RandomGrid<HexLattice>(10);
  const HexSample s = InterpolateHex(grid, CartesianToCube(100.0, -100.0));
  EXPECT_DOUBLE_EQ(s.value, 0.5);
  EXPECT_DOUBLE_EQ(s.gradient.norm(), 0.0);
}

}  // namespace
}  // namespace hex_slam
