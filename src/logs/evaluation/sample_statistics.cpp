#include "hex_slam/logs/evaluation/sample_statistics.h"

#include <algorithm>
#include <cmath>

namespace hex_slam {
namespace logs {

double SortedQuantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const double position = std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - below) * (sorted[above] - sorted[below]);
}

SampleStatistics Summarize(std::vector<double> values) {
  SampleStatistics s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.count = static_cast<int>(values.size());
  double sum = 0.0, sum_sq = 0.0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  s.mean = sum / s.count;
  double var = 0.0;
  for (double v : values) var += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(var / s.count);
  s.rmse = std::sqrt(sum_sq / s.count);
  s.median = SortedQuantile(values, 0.5);
  s.p99 = SortedQuantile(values, 0.99);
  s.max = values.back();
  return s;
}

}  // namespace logs
}  // namespace hex_slam
