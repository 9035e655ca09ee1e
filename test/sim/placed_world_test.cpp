#include "hex_slam/sim/placed_world.h"

#include <random>

#include <gtest/gtest.h>

#include "hex_slam/sim/segment_world.h"

namespace hex_slam {
namespace sim {
namespace {

TEST(PlacedWorldTest, SeesTheBaseWorldMovedByThePlacement) {
  const SegmentWorld room = SegmentWorld::TestRoom();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0), ua(-M_PI, M_PI);
  for (int k = 0; k < 20; ++k) {
    const Pose2 placement(u(rng), u(rng), ua(rng));
    const PlacedWorld placed(room, placement);
    const SegmentWorld moved = room.Transformed(placement);
    for (int i = 0; i < 100; ++i) {
      const Eigen::Vector2d p = placement * Eigen::Vector2d(u(rng), u(rng));
      const double a = ua(rng);
      const double expected = moved.CastRay(p, a, 20.0);
      const double got = placed.CastRay(p, a, 20.0);
      if (std::isinf(expected)) {
        EXPECT_TRUE(std::isinf(got));
      } else {
        EXPECT_NEAR(got, expected, 1e-9);
      }
    }
  }
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
