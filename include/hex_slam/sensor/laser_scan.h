// A planar laser scan as the core receives it: the fields of sensor_msgs/LaserScan it needs,
// without ROS. Beam i points at angle_min + i·angle_increment in the sensor frame; a negative
// increment (a lidar mounted upside down) is valid.
#ifndef HEX_SLAM_SENSOR_LASER_SCAN_H_
#define HEX_SLAM_SENSOR_LASER_SCAN_H_

#include <vector>

namespace hex_slam {

struct LaserScan {
  double stamp = 0.0;  // seconds
  double angle_min = 0.0;
  double angle_max = 0.0;
  double angle_increment = 0.0;
  double range_min = 0.0;
  double range_max = 0.0;
  std::vector<float> ranges;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_SENSOR_LASER_SCAN_H_
