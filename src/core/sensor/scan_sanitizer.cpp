#include "hex_slam/sensor/scan_sanitizer.h"

#include <cmath>
#include <sstream>

namespace hex_slam {
namespace {

// Drivers disagree on whether angle_max is the last beam's angle or one step past it.
constexpr double kSizeTolerance = 1.0;

ScanError Fail(ScanError error, const std::string& text, std::string* message) {
  *message = text;
  return error;
}

}  // namespace

const char* ScanErrorName(ScanError error) {
  switch (error) {
    case ScanError::kNone: return "ok";
    case ScanError::kEmpty: return "empty scan";
    case ScanError::kNonFiniteField: return "non-finite scan field";
    case ScanError::kZeroIncrement: return "zero angle_increment";
    case ScanError::kBadRangeLimits: return "bad range limits";
    case ScanError::kInconsistentSize: return "ranges size inconsistent with angles";
  }
  return "unknown";
}

void ScanSanitizer::UpdateDirections(const LaserScan& scan) {
  if (scan.angle_min == angle_min_ && scan.angle_increment == angle_increment_ &&
      directions_.size() == scan.ranges.size()) {
    return;
  }
  angle_min_ = scan.angle_min;
  angle_increment_ = scan.angle_increment;
  directions_.resize(scan.ranges.size());
  for (std::size_t i = 0; i < directions_.size(); ++i) {
    const double angle = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    directions_[i] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
}

ScanError SanitizeScan(const LaserScan& scan, const RangeFilter& filter,
                       std::vector<Eigen::Vector2d>* points, BeamCounts* counts,
                       std::string* message) {
  return ScanSanitizer().Sanitize(scan, filter, points, counts, message);
}

ScanError ScanSanitizer::Sanitize(const LaserScan& scan, const RangeFilter& filter,
                                  std::vector<Eigen::Vector2d>* points, BeamCounts* counts,
                                  std::string* message) {
  points->clear();
  *counts = BeamCounts();
  message->clear();
  counts->total = static_cast<int>(scan.ranges.size());
  if (scan.ranges.empty()) return Fail(ScanError::kEmpty, "scan has no ranges", message);
  for (double field : {scan.angle_min, scan.angle_max, scan.angle_increment, scan.range_min,
                       scan.range_max}) {
    if (!std::isfinite(field)) {
      return Fail(ScanError::kNonFiniteField, "angle or range limit is not finite", message);
    }
  }
  if (scan.angle_increment == 0.0) {
    return Fail(ScanError::kZeroIncrement, "angle_increment is zero", message);
  }
  if (scan.range_min < 0.0 || !(scan.range_max > scan.range_min)) {
    std::ostringstream s;
    s << "range_max (" << scan.range_max << ") must exceed range_min (" << scan.range_min
      << ") >= 0";
    return Fail(ScanError::kBadRangeLimits, s.str(), message);
  }
  const double expected = (scan.angle_max - scan.angle_min) / scan.angle_increment + 1.0;
  if (std::abs(expected - static_cast<double>(scan.ranges.size())) > kSizeTolerance + 1e-6) {
    std::ostringstream s;
    s << scan.ranges.size() << " ranges but the angles describe " << expected << " beams";
    return Fail(ScanError::kInconsistentSize, s.str(), message);
  }

  UpdateDirections(scan);
  const double lo = std::max(scan.range_min, filter.min_dist);
  const double hi = std::min(scan.range_max, filter.max_dist);
  const double no_return_from = scan.range_max - std::max(0.0, filter.range_max_margin);
  points->reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double r = scan.ranges[i];
    if (std::isnan(r)) {
      ++counts->not_a_number;
    } else if (std::isinf(r) || (filter.range_max_is_no_return && r >= no_return_from &&
                                  r <= scan.range_max)) {
      ++counts->infinite;
    } else if (r < lo || r > hi) {
      ++counts->out_of_range;
    } else {
      points->push_back(r * directions_[i]);
    }
  }
  counts->valid = static_cast<int>(points->size());
  return ScanError::kNone;
}

}  // namespace hex_slam
