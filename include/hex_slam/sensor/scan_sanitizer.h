// The one place raw ranges become points: rejects malformed scans with a reason, drops NaN, ±inf
// and out-of-range beams (counting each kind), and never throws on bad data.
#ifndef HEX_SLAM_SENSOR_SCAN_SANITIZER_H_
#define HEX_SLAM_SENSOR_SCAN_SANITIZER_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/sensor/laser_scan.h"

namespace hex_slam {

enum class ScanError {
  kNone,
  kEmpty,              // no ranges at all
  kNonFiniteField,     // an angle or range limit is NaN or inf
  kZeroIncrement,      // angle_increment == 0
  kBadRangeLimits,     // range_max <= range_min, or range_min < 0
  kInconsistentSize,   // ranges.size() disagrees with (angle_max - angle_min) / increment
};

const char* ScanErrorName(ScanError error);

struct BeamCounts {
  int total = 0;
  int valid = 0;
  int not_a_number = 0;
  int infinite = 0;      // REP-117: +inf = no return, -inf = too close; neither is a point
                         // (also r >= range_max with RangeFilter::range_max_is_no_return)
  int out_of_range = 0;  // outside the sensor's or the filter's limits, or negative
  int outside_height = 0;  // a tilted laser's points outside the height limits (Slam's filter)
  int grazing = 0;  // of the valid, inserted but not matched (Slam's laser_match_max_incidence)
};

// Beams kept must satisfy max(range_min, min_dist) <= r <= min(range_max, max_dist), and
// r < range_max - range_max_margin when range_max_is_no_return.
struct RangeFilter {
  double min_dist = 0.0;
  double max_dist = 1e9;
  // A reading at (or within range_max_margin of) the scan's range_max is a beam without a
  // return, counted as `infinite`: what Gazebo's ray sensor and drivers without +inf report, what
  // the CARMEN reader and gmapping assume, and what hector_mapping drops (it keeps only
  // r < range_max - 0.1 m). A sensor that reports no-return beams as hits at (or just short of)
  // its maximum range would otherwise put a ring of walls that travels with it into the map.
  // Off: REP-117 read literally, range_max itself a valid hit.
  bool range_max_is_no_return = true;
  double range_max_margin = 0.0;  // m
};

// Converts scans to points, remembering the beam directions of the last layout it saw so a
// stream of same-shaped scans costs no trigonometry.
class ScanSanitizer {
 public:
  // Fills `points` (sensor frame) and `counts`. On error, returns it with a readable `message`,
  // and leaves `points` empty.
  ScanError Sanitize(const LaserScan& scan, const RangeFilter& filter,
                     std::vector<Eigen::Vector2d>* points, BeamCounts* counts,
                     std::string* message);

 private:
  void UpdateDirections(const LaserScan& scan);

  double angle_min_ = 0.0;
  double angle_increment_ = 0.0;
  std::vector<Eigen::Vector2d> directions_;
};

// One-off conversion, for callers without a stream of scans.
ScanError SanitizeScan(const LaserScan& scan, const RangeFilter& filter,
                       std::vector<Eigen::Vector2d>* points, BeamCounts* counts,
                       std::string* message);

}  // namespace hex_slam

#endif  // HEX_SLAM_SENSOR_SCAN_SANITIZER_H_
