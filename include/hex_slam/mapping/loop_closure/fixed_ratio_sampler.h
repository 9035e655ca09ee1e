// Says yes to a fixed fraction of the calls, evenly spread and deterministic (Cartographer's
// FixedRatioSampler): which (node, submap) pairs the constraint search tries.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_FIXED_RATIO_SAMPLER_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_FIXED_RATIO_SAMPLER_H_

#include <cstdint>

namespace hex_slam {
namespace mapping {

class FixedRatioSampler {
 public:
  explicit FixedRatioSampler(double ratio) : ratio_(ratio) {}

  bool Pulse() {
    ++pulses_;
    if (static_cast<double>(samples_) / static_cast<double>(pulses_) < ratio_) {
      ++samples_;
      return true;
    }
    return false;
  }

 private:
  double ratio_;
  std::int64_t pulses_ = 0;
  std::int64_t samples_ = 0;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_FIXED_RATIO_SAMPLER_H_
