// The node's policy for scan stamps that go backwards. A bag played again or a simulator reset
// starts its clock over: the old map no longer matches the new scans, so a large jump back resets
// it. A small step back is a reordered or duplicated message: that scan alone is dropped.
#ifndef HEX_SLAM_NODE_ROS_INPUT_SCAN_CLOCK_H_
#define HEX_SLAM_NODE_ROS_INPUT_SCAN_CLOCK_H_

#include <optional>

namespace hex_slam {
namespace node {

enum class StampOrder {
  kInOrder,          // at or after the last accepted scan (or the first scan)
  kSlightlyEarlier,  // before it by at most the reset threshold: drop the scan
  kJumpedBack,       // before it by more: the source restarted, reset the map
};

class ScanClock {
 public:
  explicit ScanClock(double reset_threshold) : reset_threshold_(reset_threshold) {}

  StampOrder Check(double stamp) const {
    if (!last_ || stamp >= *last_) return StampOrder::kInOrder;
    return *last_ - stamp > reset_threshold_ ? StampOrder::kJumpedBack
                                             : StampOrder::kSlightlyEarlier;
  }
  // Only scans the SLAM core accepted move the clock: a malformed scan with a wild stamp must not
  // make every following good scan look late.
  void Accept(double stamp) { last_ = stamp; }
  void Reset() { last_.reset(); }
  const std::optional<double>& last() const { return last_; }

 private:
  double reset_threshold_;
  std::optional<double> last_;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_ROS_INPUT_SCAN_CLOCK_H_
