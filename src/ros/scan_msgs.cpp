#include "scan_msgs.h"

namespace hex_slam {

LaserScan ScanFromMsg(const sensor_msgs::LaserScan& msg, double stamp) {
  LaserScan scan;
  scan.stamp = stamp;
  scan.angle_min = msg.angle_min;
  scan.angle_max = msg.angle_max;
  scan.angle_increment = msg.angle_increment;
  scan.range_min = msg.range_min;
  scan.range_max = msg.range_max;
  scan.ranges = msg.ranges;
  return scan;
}

}  // namespace hex_slam
