#include "hex_slam/grid_index.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

TEST(GridIndexTest, FloorToIntEqualsStdFloorAtIntegersBetweenThemAndOnBothSides) {
  for (double x : {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1e-300, -1e-300, 2.9999999999999996,
                   -2.9999999999999996, std::nextafter(-1.0, 0.0), std::nextafter(-1.0, -2.0),
                   2147483647.0, -2147483648.0, 12345.678, -12345.678}) {
    EXPECT_EQ(FloorToInt(x), static_cast<int>(std::floor(x))) << x;
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int i = 0; i < 100000; ++i) {
    const double x = u(rng);
    ASSERT_EQ(FloorToInt(x), static_cast<int>(std::floor(x))) << x;
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
