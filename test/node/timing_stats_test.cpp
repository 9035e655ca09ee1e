#include "timing_stats.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

TEST(TimingStatsTest, MeansMaximaAndSummary) {
  TimingStats stats;
  EXPECT_EQ(stats.callback_mean(), 0.0);
  stats.Add(3.0, 2.0);
  stats.Add(5.0, 4.5);
  EXPECT_EQ(stats.count(), 2);
  EXPECT_DOUBLE_EQ(stats.callback_mean(), 4.0);
  EXPECT_DOUBLE_EQ(stats.core_mean(), 3.25);
  EXPECT_DOUBLE_EQ(stats.overhead_mean(), 0.75);
  EXPECT_DOUBLE_EQ(stats.callback_max(), 5.0);
  EXPECT_DOUBLE_EQ(stats.overhead_max(), 1.0);
  EXPECT_NE(stats.Summary().find("scans=2 callback_mean_ms=4.000 core_mean_ms=3.250"),
            std::string::npos)
      << stats.Summary();
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
