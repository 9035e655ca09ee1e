#include "hex_slam/sensor/scan_sanitizer.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace hex_slam {
namespace {

LaserScan FourBeams() {
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = M_PI / 2;
  scan.angle_max = 3 * M_PI / 2;
  scan.range_min = 0.1;
  scan.range_max = 10.0;
  scan.ranges = {1.0f, 2.0f, 3.0f, 4.0f};
  return scan;
}

struct Result {
  ScanError error;
  std::vector<Eigen::Vector2d> points;
  BeamCounts counts;
  std::string message;
};

Result Sanitize(const LaserScan& scan, RangeFilter filter = RangeFilter()) {
  Result r;
  r.error = SanitizeScan(scan, filter, &r.points, &r.counts, &r.message);
  return r;
}

TEST(ScanSanitizerTest, ConvertsValidBeamsToPoints) {
  const Result r = Sanitize(FourBeams());
  ASSERT_EQ(r.error, ScanError::kNone);
  ASSERT_EQ(r.points.size(), 4u);
  EXPECT_NEAR((r.points[1] - Eigen::Vector2d(0.0, 2.0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((r.points[3] - Eigen::Vector2d(0.0, -4.0)).norm(), 0.0, 1e-6);
}

TEST(ScanSanitizerTest, DropsNanInfNegativeAndOutOfRangeBeamsAndCountsThem) {
  LaserScan scan = FourBeams();
  const float inf = std::numeric_limits<float>::infinity();
  scan.ranges = {std::nanf(""), inf, -inf, -1.0f, 0.05f, 11.0f, 5.0f, 2.0f};
  scan.angle_increment = M_PI / 4;
  scan.angle_max = 7 * M_PI / 4;
  const Result r = Sanitize(scan, RangeFilter{0.0, 8.0});
  ASSERT_EQ(r.error, ScanError::kNone);
  EXPECT_EQ(r.counts.total, 8);
  EXPECT_EQ(r.counts.not_a_number, 1);
  EXPECT_EQ(r.counts.infinite, 2);
  EXPECT_EQ(r.counts.out_of_range, 3);  // -1 (negative), 0.05 (< range_min), 11 (> range_max)
  EXPECT_EQ(r.counts.valid, 2);
  EXPECT_EQ(r.points.size(), 2u);
}

TEST(ScanSanitizerTest, AReadingAtRangeMaxIsNoReturnUnlessToldOtherwise) {
  LaserScan scan = FourBeams();  // range_max 10
  scan.ranges = {10.0f, 9.95f, 9.85f, 4.0f};
  RangeFilter filter;
  Result r = Sanitize(scan, filter);  // the default: exactly range_max is no return
  EXPECT_EQ(r.counts.infinite, 1);
  EXPECT_EQ(r.counts.valid, 3);
  filter.range_max_margin = 0.1;  // hector's: within 0.1 m of range_max too
  r = Sanitize(scan, filter);
  EXPECT_EQ(r.counts.infinite, 2);
  EXPECT_EQ(r.counts.valid, 2);
  EXPECT_NEAR(r.points[0].norm(), 9.85, 1e-5);
  filter.range_max_is_no_return = false;  // REP-117 read literally: range_max is a hit
  r = Sanitize(scan, filter);
  EXPECT_EQ(r.counts.infinite, 0);
  EXPECT_EQ(r.counts.valid, 4);
  // Past range_max stays out of range either way.
  scan.ranges = {10.5f, 1.0f, 1.0f, 1.0f};
  EXPECT_EQ(Sanitize(scan, RangeFilter()).counts.out_of_range, 1);
}

TEST(ScanSanitizerTest, FilterLimitsTightenTheSensorLimits) {
  const Result r = Sanitize(FourBeams(), RangeFilter{1.5, 3.5});
  ASSERT_EQ(r.error, ScanError::kNone);
  EXPECT_EQ(r.counts.valid, 2);
}

TEST(ScanSanitizerTest, NegativeIncrementIsAnUpsideDownLidarNotAnError) {
  LaserScan scan = FourBeams();
  scan.angle_increment = -M_PI / 2;
  scan.angle_max = -3 * M_PI / 2;
  const Result r = Sanitize(scan);
  ASSERT_EQ(r.error, ScanError::kNone);
  EXPECT_NEAR((r.points[1] - Eigen::Vector2d(0.0, -2.0)).norm(), 0.0, 1e-6);
}

TEST(ScanSanitizerTest, RejectsMalformedScansWithAReason) {
  LaserScan empty = FourBeams();
  empty.ranges.clear();
  EXPECT_EQ(Sanitize(empty).error, ScanError::kEmpty);

  LaserScan zero = FourBeams();
  zero.angle_increment = 0.0;
  EXPECT_EQ(Sanitize(zero).error, ScanError::kZeroIncrement);

  LaserScan limits = FourBeams();
  limits.range_max = limits.range_min;
  EXPECT_EQ(Sanitize(limits).error, ScanError::kBadRangeLimits);
  limits.range_min = -1.0;
  limits.range_max = 5.0;
  EXPECT_EQ(Sanitize(limits).error, ScanError::kBadRangeLimits);

  LaserScan too_long = FourBeams();
  too_long.ranges.resize(40, 1.0f);
  const Result r = Sanitize(too_long);
  EXPECT_EQ(r.error, ScanError::kInconsistentSize);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(r.points.empty());

  LaserScan nan_field = FourBeams();
  nan_field.angle_min = std::nan("");
  EXPECT_EQ(Sanitize(nan_field).error, ScanError::kNonFiniteField);
}

TEST(ScanSanitizerTest, ToleratesTheCommonOffByOneInAngleMax) {
  LaserScan scan = FourBeams();
  scan.angle_max = 2 * M_PI;  // one step past the last beam
  EXPECT_EQ(Sanitize(scan).error, ScanError::kNone);
}

}  // namespace
}  // namespace hex_slam
