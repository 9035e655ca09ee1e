// libFuzzer target: one bag message's bytes, decoded as hex_slam_offline's bag reader decodes
// them. The first byte picks the type (LaserScan, TFMessage, Odometry); a decoded scan goes on
// through the core's scan sanitizer, as the reader's scans do.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "hex_slam/common/input_limits.h"
#include "hex_slam/logs/bag_messages.h"
#include "hex_slam/sensor/scan_sanitizer.h"
#include "scan_msgs.h"

namespace {

void Scan(const std::uint8_t* data, std::size_t size) {
  sensor_msgs::LaserScan msg;
  if (!hex_slam::logs::DecodeLaserScan(data, size, &msg).empty()) return;
  HEX_SLAM_FUZZ_CHECK(static_cast<long>(msg.ranges.size()) <= hex_slam::kMaxScanReadings);
  HEX_SLAM_FUZZ_CHECK(std::isfinite(msg.angle_increment) && std::isfinite(msg.range_max));
  const hex_slam::LaserScan scan = hex_slam::ScanFromMsg(msg, msg.header.stamp.toSec());
  std::vector<Eigen::Vector2d> points;
  hex_slam::BeamCounts counts;
  std::string message;
  const hex_slam::RangeFilter filter{0.4, 30.0};
  if (hex_slam::SanitizeScan(scan, filter, &points, &counts, &message) !=
      hex_slam::ScanError::kNone) {
    return;
  }
  for (const Eigen::Vector2d& p : points) HEX_SLAM_FUZZ_CHECK(p.allFinite() && p.norm() <= 30.0);
}

void Tf(const std::uint8_t* data, std::size_t size) {
  tf2_msgs::TFMessage msg;
  if (!hex_slam::logs::DecodeTfMessage(data, size, &msg).empty()) return;
  for (const geometry_msgs::TransformStamped& t : msg.transforms) {
    HEX_SLAM_FUZZ_CHECK(hex_slam::logs::CheckTransform(t).empty());
  }
}

void Odometry(const std::uint8_t* data, std::size_t size) {
  nav_msgs::Odometry msg;
  if (!hex_slam::logs::DecodeOdometry(data, size, &msg).empty()) return;
  const geometry_msgs::Point& p = msg.pose.pose.position;
  HEX_SLAM_FUZZ_CHECK(std::abs(p.x) <= hex_slam::kMaxAbsCoordinate &&
                      std::abs(p.y) <= hex_slam::kMaxAbsCoordinate);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  switch (data[0] % 3) {
    case 0: Scan(data + 1, size - 1); break;
    case 1: Tf(data + 1, size - 1); break;
    default: Odometry(data + 1, size - 1); break;
  }
  return 0;
}
