#include "hex_slam/logs/stamp_order.h"

namespace hex_slam {
namespace logs {

int MakeStampsIncreasing(const std::vector<double>& stamps, double min_step,
                         std::vector<double>* out) {
  if (out != &stamps) *out = stamps;
  std::vector<double>& t = *out;
  int changed = 0;
  for (std::size_t i = t.size(); i-- > 1;) {
    const bool later = min_step > 0.0 ? t[i - 1] > t[i] - min_step : t[i - 1] > t[i];
    if (later) {
      t[i - 1] = t[i] - min_step;
      ++changed;
    }
  }
  return changed;
}

int MakeStampsNonDecreasing(const std::vector<double>& stamps, std::vector<double>* out) {
  return MakeStampsIncreasing(stamps, 0.0, out);
}

int CountBackwardSteps(const std::vector<double>& stamps) {
  int count = 0;
  for (std::size_t i = 1; i < stamps.size(); ++i) count += stamps[i] < stamps[i - 1] ? 1 : 0;
  return count;
}

}  // namespace logs
}  // namespace hex_slam
