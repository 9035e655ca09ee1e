// sensor_msgs/LaserScan to the core's scan, shared by every ROS program that reads scans (the
// node from /scan, hex_slam_offline from a bag), so both hand the core the same fields.
#ifndef HEX_SLAM_ROS_SCAN_MSGS_H_
#define HEX_SLAM_ROS_SCAN_MSGS_H_

#include <sensor_msgs/LaserScan.h>

#include "hex_slam/sensor/laser_scan.h"

namespace hex_slam {

// The scan in the laser's own frame (its mount, however tilted or flipped, is applied by the
// core's SensorMount), stamped `stamp` (s). Ranges are copied as they are: NaN, infinite and
// out-of-range ones are left for the core's sanitizer to count and drop.
LaserScan ScanFromMsg(const sensor_msgs::LaserScan& msg, double stamp);

}  // namespace hex_slam

#endif  // HEX_SLAM_ROS_SCAN_MSGS_H_
