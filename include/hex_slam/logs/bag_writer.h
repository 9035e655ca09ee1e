// Logs as ROS 1 bags, shaped the way hex_slam_node (and hector_mapping) consume them:
//   /scan       sensor_msgs/LaserScan in laser_frame
//   /tf         odom_frame -> base_frame at every scan that has odometry
//   /tf_static  base_frame -> laser_frame once (latched, so rosbag play re-sends it)
//   /odom       nav_msgs/Odometry, odom_frame -> base_frame, at the same stamps
// Stamps are made non-decreasing first (stamp_order.h): a replay must not go back in time. Links
// rosbag (library hex_slam_bag).
#ifndef HEX_SLAM_LOGS_BAG_WRITER_H_
#define HEX_SLAM_LOGS_BAG_WRITER_H_

#include <string>
#include <vector>

#include "hex_slam/logs/log_scan.h"

namespace hex_slam {
namespace logs {

struct BagWriteOptions {
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";
  std::string laser_frame = "laser";
  std::string base_frame = "base_link";
  std::string odom_frame = "odom";
};

struct BagWriteReport {
  int scans = 0;
  int odometry = 0;       // scans with odometry (tf + Odometry message each)
  int stamps_lowered = 0;
  bool mounting_varies = false;  // the log's laser mounting changed; the first one was written
};

// Writes the bag beside `path` and renames it over `path` once complete, so a failed or
// interrupted conversion leaves no half-written bag. Returns an empty string or an error.
std::string WriteLogAsBag(const std::vector<LogScan>& scans, const std::string& path,
                          const BagWriteOptions& options, BagWriteReport* report);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_BAG_WRITER_H_
