#include "hex_slam/geometry/grid_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

TEST(GridIndexTest, FloorToIntEqualsStdFloorAtIntegersBetweenThemAndOnBothSides) {
  for (double x : {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1e-300, -1e-300, 2.9999999999999996,
                   -2.9999999999999996, std::nextafter(-1.0, 0.0), std::nextafter(-1.0, -2.0),
                   12345.678, -12345.678}) {
    EXPECT_EQ(FloorToInt(x), static_cast<int>(std::floor(x))) << x;
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int i = 0; i < 100000; ++i) {
    const double x = u(rng);
    ASSERT_EQ(FloorToInt(x), static_cast<int>(std::floor(x))) << x;
  }
}

// The values that used to be undefined behaviour in the float-to-int casts (issue 12: UBSan's
// float-cast-overflow at grid_index.h, then signed overflow, then out-of-bounds writes).
const double kInf = std::numeric_limits<double>::infinity();
const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kHostile[] = {kNan, -kNan, kInf, -kInf, 1e300, -1e300, 1e15, -1e15, 4294967296.0,
                           -4294967296.0, 2147483648.0, -2147483649.0, 268435456.5, -268435456.5,
                           std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                           std::numeric_limits<double>::denorm_min()};

// The oracle: the mathematical floor / ceil / round, clamped to the index range, NaN as +limit.
long long Clamped(double v) {
  const double limit = kMaxCellIndex;
  if (std::isnan(v)) return kMaxCellIndex;
  return static_cast<long long>(std::min(limit, std::max(-limit, v)));
}

TEST(GridIndexTest, AnyDoubleGivesTheClampedFloorCeilAndRound) {
  for (double x : kHostile) {
    EXPECT_EQ(FloorToInt(x), Clamped(std::floor(x))) << x;
    EXPECT_EQ(RoundToInt(x), Clamped(std::round(x))) << x;
    // NaN's ceiling is the other end (ceil(x) = -floor(-x)); either is outside every map.
    EXPECT_EQ(CeilToInt(x), std::isnan(x) ? -kMaxCellIndex : Clamped(std::ceil(x))) << x;
  }
  // Inside the range nothing changes, up to the limits themselves.
  for (double x : {-268435456.0, 268435455.5, -0.5, 0.5, 7.25, -7.25}) {
    EXPECT_EQ(FloorToInt(x), static_cast<long long>(std::floor(x))) << x;
    EXPECT_EQ(CeilToInt(x), static_cast<long long>(std::ceil(x))) << x;
    EXPECT_EQ(RoundToInt(x), static_cast<long long>(std::round(x))) << x;
  }
}

TEST(GridIndexTest, FloorHalfRoundsDown) {
  EXPECT_EQ(FloorHalf(3), 1);
  EXPECT_EQ(FloorHalf(-3), -2);
  EXPECT_EQ(FloorHalf(-4), -2);
  EXPECT_EQ(FloorHalf(0), 0);
}

}  // namespace
}  // namespace hex_slam
