// A robot's motion along a polyline: drive straight at constant speed, turn in place at each
// waypoint, sampled at the lidar's rate. Deterministic: the same inputs give the same poses.
#ifndef HEX_SLAM_SIM_WAYPOINT_PATH_H_
#define HEX_SLAM_SIM_WAYPOINT_PATH_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace sim {

struct PathMotion {
  double linear_speed = 0.3;   // m/s
  double angular_speed = 0.6;  // rad/s, turning in place
  double rate = 10.0;          // samples per second
};

// Starts at waypoints[0] facing `start_heading`, turns towards the next waypoint, drives, and so
// on. The returned poses are 1/rate seconds apart.
std::vector<Pose2> SampleWaypointPath(const std::vector<Eigen::Vector2d>& waypoints,
                                      double start_heading, const PathMotion& motion);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_WAYPOINT_PATH_H_
