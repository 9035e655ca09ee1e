#include "hex_slam/matching/precomputation_grid.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"
#include "random_maps.h"

namespace hex_slam {
namespace matching {
namespace {

using testing_util::CellValue;
using testing_util::RandomMap;

template <class T>
class PrecomputationGridTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(PrecomputationGridTest, Lattices);

// Depth k at z is the largest cell value over z + [0, 2^k)² in lattice coordinates, checked by
// reading every window's cells through the map's accessors, over the boxes and a margin beyond.
TYPED_TEST(PrecomputationGridTest, EveryDepthIsTheMaximumOverItsWindow) {
  constexpr double kUnknown = 0.1;
  std::mt19937_64 rng(7);
  const GridMap<TypeParam> grid = RandomMap<TypeParam>(0.15, &rng);
  const PrecomputationGridStack stack(grid, 4, kUnknown);
  ASSERT_EQ(stack.max_depth(), 4);
  ASSERT_GT(stack.cells().size().minCoeff(), 0);
  for (int depth = 0; depth <= stack.max_depth(); ++depth) {
    const PrecomputationGrid& g = stack.Get(depth);
    const int width = 1 << depth;
    EXPECT_TRUE((g.size() == stack.cells().size() + width - 1).all()) << "depth " << depth;
    const int margin = 3;
    for (int y = g.origin().y() - margin; y <= g.last().y() + margin; ++y) {
      for (int x = g.origin().x() - margin; x <= g.last().x() + margin; ++x) {
        double expected = 0.0;
        for (int j = 0; j < width; ++j) {
          for (int i = 0; i < width; ++i) {
            expected = std::max(expected, CellValue(grid, Eigen::Array2i(x + i, y + j), kUnknown));
          }
        }
        ASSERT_FLOAT_EQ(g.At(Eigen::Array2i(x, y)), expected)
            << "depth " << depth << " at " << x << ", " << y;
      }
    }
  }
}

TYPED_TEST(PrecomputationGridTest, AMapWithNothingKnownHasAnEmptyBoxAndReadsUnknown) {
  const GridMap<TypeParam> grid(TypeParam(0.1), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                                GridGrowthPolicy(),
                                Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
  const PrecomputationGridStack stack(grid, 3, 0.25f);
  EXPECT_EQ(stack.cells().size().prod(), 0);
  EXPECT_NEAR(stack.Get(3).At(Eigen::Array2i(0, 0)), 0.25, 0.5 / 255.0);
}

// Stored as a byte, a probability moves by at most half a step of 1/255, and order is kept (so
// the max-pooled bounds stay bounds of the stored scores); what is not a probability is clamped.
TEST(QuantizedProbabilityTest, IsWithinHalfAStepAndKeepsTheOrder) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 100000; ++i) {
    const float a = u(rng), b = u(rng);
    EXPECT_NEAR(QuantizedProbability(a), a, 0.5 / 255.0 + 1e-7) << a;
    if (a <= b) {
      EXPECT_LE(QuantizeValue(a), QuantizeValue(b)) << a << " " << b;
    }
  }
  EXPECT_EQ(QuantizeValue(0.0f), 0);
  EXPECT_EQ(QuantizeValue(1.0f), 255);
  EXPECT_EQ(QuantizeValue(-0.5f), 0);
  EXPECT_EQ(QuantizeValue(2.0f), 255);
  EXPECT_EQ(QuantizeValue(std::nanf("")), 0);
}

}  // namespace
}  // namespace matching
}  // namespace hex_slam
