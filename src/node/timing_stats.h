// What a scan costs the node: the SLAM thread's work on it next to the core's ProcessScan inside
// it (the difference is the node's overhead: conversion, tf lookups, the lock, publishing), and
// its latency, from the moment the subscriber received it to its pose being published (queueing
// included). Percentiles come from a histogram of 1 % wide bins, so memory stays fixed however
// long the node runs.
#ifndef HEX_SLAM_NODE_TIMING_STATS_H_
#define HEX_SLAM_NODE_TIMING_STATS_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace hex_slam {
namespace node {

// Durations in ms with 1 % resolution from 0.01 ms to ~10 s; shorter ones count in the first bin,
// longer ones in the last (the maximum is kept exactly).
class LatencyHistogram {
 public:
  void Add(double ms) {
    ++count_;
    max_ = std::max(max_, ms);
    const double position = std::log(std::max(ms, kFirstMs) / kFirstMs) / std::log(kGrowth);
    const int bin = std::min(kBins - 1, static_cast<int>(position));
    ++bins_[bin];
  }
  long count() const { return count_; }
  double max() const { return max_; }
  // The upper edge of the bin holding the q-quantile (0 < q <= 1); 0 without samples.
  double Quantile(double q) const {
    if (count_ == 0) return 0.0;
    const double target = q * static_cast<double>(count_);
    long seen = 0;
    for (int bin = 0; bin < kBins; ++bin) {
      seen += bins_[bin];
      if (static_cast<double>(seen) >= target) {
        return std::min(max_, kFirstMs * std::pow(kGrowth, bin + 1));
      }
    }
    return max_;
  }

 private:
  static constexpr double kFirstMs = 0.01;
  static constexpr double kGrowth = 1.01;
  static constexpr int kBins = 1400;  // 0.01 ms * 1.01^1400 ~ 11 s
  std::array<std::uint32_t, kBins> bins_{};
  long count_ = 0;
  double max_ = 0.0;
};

class TimingStats {
 public:
  // `work_ms`: the SLAM thread's time on the scan; `latency_ms`: from receipt to publication.
  void Add(double work_ms, double core_ms, double latency_ms) {
    ++count_;
    work_sum_ += work_ms;
    core_sum_ += core_ms;
    overhead_sum_ += work_ms - core_ms;
    work_max_ = std::max(work_max_, work_ms);
    overhead_max_ = std::max(overhead_max_, work_ms - core_ms);
    latency_.Add(latency_ms);
  }
  long count() const { return count_; }
  double callback_mean() const { return count_ ? work_sum_ / count_ : 0.0; }
  double core_mean() const { return count_ ? core_sum_ / count_ : 0.0; }
  double overhead_mean() const { return count_ ? overhead_sum_ / count_ : 0.0; }
  double callback_max() const { return work_max_; }
  double overhead_max() const { return overhead_max_; }
  const LatencyHistogram& latency() const { return latency_; }

  // One line of key=value pairs, for logs and scripts.
  std::string Summary() const {
    char line[320];
    std::snprintf(line, sizeof line,
                  "scans=%ld callback_mean_ms=%.3f core_mean_ms=%.3f overhead_mean_ms=%.3f "
                  "callback_max_ms=%.3f overhead_max_ms=%.3f latency_p50_ms=%.3f "
                  "latency_p99_ms=%.3f latency_max_ms=%.3f",
                  count_, callback_mean(), core_mean(), overhead_mean(), work_max_,
                  overhead_max_, latency_.Quantile(0.5), latency_.Quantile(0.99), latency_.max());
    return line;
  }

 private:
  long count_ = 0;
  double work_sum_ = 0.0;
  double core_sum_ = 0.0;
  double overhead_sum_ = 0.0;
  double work_max_ = 0.0;
  double overhead_max_ = 0.0;
  LatencyHistogram latency_;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_TIMING_STATS_H_
