// Summary figures of a sample of errors or timings. The standard deviation is the population one
// (divide by n), as numpy and the published relations figures use.
#ifndef HEX_SLAM_LOGS_EVALUATION_SAMPLE_STATISTICS_H_
#define HEX_SLAM_LOGS_EVALUATION_SAMPLE_STATISTICS_H_

#include <vector>

namespace hex_slam {
namespace logs {

struct SampleStatistics {
  int count = 0;
  double mean = 0.0;
  double stddev = 0.0;
  double rmse = 0.0;  // sqrt(mean of squares)
  double median = 0.0;
  double p99 = 0.0;  // 99th percentile, interpolated between order statistics
  double max = 0.0;
};

// All zero for an empty sample.
SampleStatistics Summarize(std::vector<double> values);

// The q-quantile (0..1) of sorted values, linearly interpolated; 0 for an empty sample.
double SortedQuantile(const std::vector<double>& sorted, double q);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_EVALUATION_SAMPLE_STATISTICS_H_
