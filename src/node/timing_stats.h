// What the scan callback costs next to the core's ProcessScan inside it: the node's overhead is
// the difference (conversion, tf lookups, the lock, publishing pose and tf).
#ifndef HEX_SLAM_NODE_TIMING_STATS_H_
#define HEX_SLAM_NODE_TIMING_STATS_H_

#include <algorithm>
#include <cstdio>
#include <string>

namespace hex_slam {
namespace node {

class TimingStats {
 public:
  void Add(double callback_ms, double core_ms) {
    ++count_;
    callback_sum_ += callback_ms;
    core_sum_ += core_ms;
    overhead_sum_ += callback_ms - core_ms;
    callback_max_ = std::max(callback_max_, callback_ms);
    overhead_max_ = std::max(overhead_max_, callback_ms - core_ms);
  }
  long count() const { return count_; }
  double callback_mean() const { return count_ ? callback_sum_ / count_ : 0.0; }
  double core_mean() const { return count_ ? core_sum_ / count_ : 0.0; }
  double overhead_mean() const { return count_ ? overhead_sum_ / count_ : 0.0; }
  double callback_max() const { return callback_max_; }
  double overhead_max() const { return overhead_max_; }

  // One line of key=value pairs, for logs and scripts.
  std::string Summary() const {
    char line[256];
    std::snprintf(line, sizeof line,
                  "scans=%ld callback_mean_ms=%.3f core_mean_ms=%.3f overhead_mean_ms=%.3f "
                  "callback_max_ms=%.3f overhead_max_ms=%.3f",
                  count_, callback_mean(), core_mean(), overhead_mean(), callback_max_,
                  overhead_max_);
    return line;
  }

 private:
  long count_ = 0;
  double callback_sum_ = 0.0;
  double core_sum_ = 0.0;
  double overhead_sum_ = 0.0;
  double callback_max_ = 0.0;
  double overhead_max_ = 0.0;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_TIMING_STATS_H_
