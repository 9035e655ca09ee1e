#include "hex_slam/logs/evaluation/sample_statistics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hex_slam {
namespace logs {
namespace {

TEST(SampleStatisticsTest, HandComputedSample) {
  // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, population std 2, sum of squares 232.
  const SampleStatistics s = Summarize({9, 2, 4, 4, 5, 4, 5, 7});
  EXPECT_EQ(s.count, 8);
  EXPECT_DOUBLE_EQ(s.mean, 5.0);
  EXPECT_DOUBLE_EQ(s.stddev, 2.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(232.0 / 8.0));
  EXPECT_DOUBLE_EQ(s.median, 4.5);
  EXPECT_DOUBLE_EQ(s.max, 9.0);
  // 99th percentile: position 0.99 * 7 = 6.93 between 7 and 9.
  EXPECT_NEAR(s.p99, 7.0 + 0.93 * 2.0, 1e-12);
}

TEST(SampleStatisticsTest, EmptyAndSingleSamples) {
  const SampleStatistics empty = Summarize({});
  EXPECT_EQ(empty.count, 0);
  EXPECT_EQ(empty.mean, 0.0);
  const SampleStatistics one = Summarize({3.0});
  EXPECT_EQ(one.count, 1);
  EXPECT_EQ(one.median, 3.0);
  EXPECT_EQ(one.p99, 3.0);
  EXPECT_EQ(one.stddev, 0.0);
}

TEST(SampleStatisticsTest, QuantilesInterpolateAndClamp) {
  const std::vector<double> sorted = {0.0, 10.0};
  EXPECT_DOUBLE_EQ(SortedQuantile(sorted, 0.25), 2.5);
  EXPECT_DOUBLE_EQ(SortedQuantile(sorted, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(SortedQuantile(sorted, 2.0), 10.0);
  EXPECT_DOUBLE_EQ(SortedQuantile({}, 0.5), 0.0);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
