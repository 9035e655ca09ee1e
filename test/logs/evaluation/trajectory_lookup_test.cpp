#include "hex_slam/logs/evaluation/trajectory_lookup.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hex_slam {
namespace logs {
namespace {

std::vector<io::StampedPose> Unordered() {
  // Out of order on purpose, as a log with backward stamps writes them.
  return {{2.0, Pose2(2, 0, 0)}, {1.0, Pose2(1, 0, 0)}, {1.2, Pose2(1.2, 0.5, 3.0)},
          {1.4, Pose2(1.4, 0.5, -3.0)}};
}

TEST(TrajectoryLookupTest, SameStampIsTakenAsIs) {
  const TrajectoryLookup lookup(Unordered());
  const auto p = lookup.At(1.2004, LookupOptions());
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->x, 1.2);
  EXPECT_EQ(p->theta, 3.0);
}

TEST(TrajectoryLookupTest, InterpolatesAcrossAShortGapAlongTheShorterArc) {
  const TrajectoryLookup lookup(Unordered());
  LookupOptions options;
  options.max_gap = 0.25;
  const auto p = lookup.At(1.3, options);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x, 1.3, 1e-12);
  EXPECT_NEAR(p->y, 0.5, 1e-12);
  // 3.0 and -3.0 rad are 0.28 rad apart through pi, not 6 rad through 0.
  EXPECT_NEAR(std::abs(p->theta), M_PI, 1e-9);
}

TEST(TrajectoryLookupTest, NoPoseAcrossALongGapOrOutsideTheSpan) {
  const TrajectoryLookup lookup(Unordered());
  LookupOptions options;
  options.max_gap = 0.25;
  EXPECT_FALSE(lookup.At(1.7, options).has_value());  // 1.4 .. 2.0 is 0.6 s
  EXPECT_FALSE(lookup.At(0.5, options).has_value());
  EXPECT_FALSE(lookup.At(2.5, options).has_value());
  options.max_gap = 1.0;
  EXPECT_TRUE(lookup.At(1.7, options).has_value());
  EXPECT_FALSE(TrajectoryLookup({}).At(1.0, options).has_value());
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
