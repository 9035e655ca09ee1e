#include "timing_stats.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

TEST(TimingStatsTest, MeansMaximaAndSummary) {
  TimingStats stats;
  EXPECT_EQ(stats.callback_mean(), 0.0);
  stats.Add(3.0, 2.0, 3.5);
  stats.Add(5.0, 4.5, 9.0);
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

// Quantiles against the sorted samples (the oracle): within the histogram's 1 % bins.
TEST(TimingStatsTest, LatencyQuantilesMatchSortedSamples) {
  LatencyHistogram histogram;
  std::vector<double> samples;
  std::mt19937 rng(4);
  std::lognormal_distribution<double> latency(0.0, 1.0);  // ms, a long tail
  for (int i = 0; i < 5000; ++i) {
    samples.push_back(latency(rng));
    histogram.Add(samples.back());
  }
  std::sort(samples.begin(), samples.end());
  for (double q : {0.5, 0.9, 0.99}) {
    const double exact = samples[static_cast<std::size_t>(std::ceil(q * samples.size())) - 1];
    EXPECT_NEAR(histogram.Quantile(q), exact, 0.011 * exact) << q;
  }
  EXPECT_DOUBLE_EQ(histogram.max(), samples.back());
  EXPECT_EQ(LatencyHistogram().Quantile(0.5), 0.0);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
