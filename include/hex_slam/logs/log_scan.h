// One laser scan as a log delivers it, with what the log knows about where it was taken. The
// readers (CARMEN, rosbag) produce these in recording order; the offline runner consumes them.
#ifndef HEX_SLAM_LOGS_LOG_SCAN_H_
#define HEX_SLAM_LOGS_LOG_SCAN_H_

#include <optional>

#include "hex_slam/sensor/laser_scan.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace logs {

struct LogScan {
  LaserScan scan;                 // scan.stamp is the log's own stamp, whatever its order
  Pose2 sensor_pose;              // the laser in the base frame
  std::optional<Pose2> odometry;  // the base's odometry pose at the scan, when the log has it
};

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_LOG_SCAN_H_
