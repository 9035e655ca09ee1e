#include "hex_slam/sim/lidar_model.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/sim/segment_world.h"

namespace hex_slam {
namespace sim {
namespace {

// One wall 2 m ahead, across x; every beam pointing away from it has no return within range.
SegmentWorld OneWall() {
  SegmentWorld world;
  world.AddSegment({2.0, -50.0}, {2.0, 50.0});
  return world;
}

TEST(LidarModelTest, MaxRangeGhostsReplaceNoReturnsOnlyWhenAsked) {
  LidarModel lidar;
  lidar.beams = 8;  // 45° apart from -180°: beams 3, 4, 5 face the wall (-45°, 0°, 45°)
  lidar.range_noise_stddev = 0.0;
  lidar.range_max = 6.0;
  std::mt19937_64 rng(0);
  const LaserScan plain = SimulateScan(OneWall(), Pose2(), lidar, 0.0, &rng);
  lidar.max_range_ghosts = true;
  const LaserScan ghosts = SimulateScan(OneWall(), Pose2(), lidar, 0.0, &rng);
  lidar.max_range_ghost_margin = 0.05;
  const LaserScan short_ghosts = SimulateScan(OneWall(), Pose2(), lidar, 0.0, &rng);
  for (int i = 0; i < lidar.beams; ++i) {
    const double expected = 2.0 / std::cos(plain.angle_min + i * plain.angle_increment);
    if (i >= 3 && i <= 5) {  // a real return: the same in all three
      EXPECT_NEAR(plain.ranges[i], expected, 1e-5) << i;
      EXPECT_EQ(ghosts.ranges[i], plain.ranges[i]) << i;
      EXPECT_EQ(short_ghosts.ranges[i], plain.ranges[i]) << i;
    } else {
      EXPECT_TRUE(std::isinf(plain.ranges[i]) && plain.ranges[i] > 0) << i;  // REP-117
      EXPECT_FLOAT_EQ(ghosts.ranges[i], 6.0f) << i;
      EXPECT_FLOAT_EQ(short_ghosts.ranges[i], 5.95f) << i;
    }
  }
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
