// ROS 1 bags as logs: sensor_msgs/LaserScan messages of one topic, with the laser's mounting and
// the odometry taken from the bag's /tf and /tf_static, or from a nav_msgs/Odometry topic.
// Links rosbag and tf2 (library hex_slam_bag); everything downstream of it is ROS-free.
//
// Where each part comes from, in order of preference:
//   mounting  — the sensor_pose option; else tf base_frame <- scan frame at the scan's stamp;
//               else, in a bag without any tf, the identity (laser at the base);
//   odometry  — tf odom_frame <- base_frame at the scan's stamp; else the Odometry topic,
//               interpolated to the stamp; else none.
// A scan whose mounting tf cannot be looked up is dropped and counted, never guessed. Every message
// is size-capped and checked before use (bag_messages.h).
#ifndef HEX_SLAM_LOGS_BAG_READER_H_
#define HEX_SLAM_LOGS_BAG_READER_H_

#include <optional>
#include <string>
#include <vector>

#include "hex_slam/logs/log_scan.h"

namespace hex_slam {
namespace logs {

struct BagReadOptions {
  std::string scan_topic = "/scan";  // a relative name ("scan", as the node's) means "/scan"
  // nav_msgs/Odometry topic; empty: the bag's Odometry topic, if it has exactly one.
  std::string odom_topic;
  std::string base_frame = "base_link";  // hector_mapping's names
  std::string odom_frame = "odom";
  std::optional<Pose2> sensor_pose;  // the laser in the base frame, overriding tf
  bool read_odometry = true;
  // Largest gap (s) between Odometry messages interpolated across at a scan's stamp.
  double odometry_max_gap = 0.5;
  // A message that fails its checks (bag_messages.h: corrupt, non-finite or out-of-bounds
  // fields; a tf mounting farther than kMaxSensorOffset) is an error naming it; with this set it
  // is skipped and counted.
  bool skip_bad_messages = false;
};

struct BagLog {
  std::vector<LogScan> scans;  // in the bag's order
  std::string mounting_source;  // where sensor_pose came from
  std::string odometry_source;  // where odometry came from ("none" if nowhere)
  int scans_in_bag = 0;
  int dropped_no_transform = 0;  // scans without a mounting transform
  int scans_without_odometry = 0;  // scans kept, but no odometry at their stamp
  std::string first_drop;  // why the first dropped scan was dropped
  int bad_messages = 0;    // skipped (skip_bad_messages only)
  std::string first_bad_message;
};

// Returns an empty string or an error (unreadable or corrupt bag, no such topic, no usable scan).
std::string ReadBag(const std::string& path, const BagReadOptions& options, BagLog* log);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_BAG_READER_H_
