// Waypoint path files: where a simulated robot drives, as YAML.
//
//   format: hex_slam_waypoint_path
//   version: 1
//   start_heading: 0.0        # rad, the robot's heading at the first waypoint
//   waypoints:                # metres, in the world's frame
//     - [0.05, 4.95]
//     - [0.45, 4.95]
#ifndef HEX_SLAM_SIM_PATH_FILE_H_
#define HEX_SLAM_SIM_PATH_FILE_H_

#include <string>
#include <vector>

#include <Eigen/Core>

namespace hex_slam {
namespace sim {

struct WaypointPath {
  double start_heading = 0.0;
  std::vector<Eigen::Vector2d> waypoints;
};

constexpr const char* kWaypointPathFormat = "hex_slam_waypoint_path";
constexpr int kWaypointPathVersion = 1;
// A path file with more waypoints than this is refused: it is not a path a robot drives.
constexpr int kMaxWaypoints = 100000;

// Returns an empty string or an error naming the file and what is wrong (missing or unknown
// key, wrong format or version, a waypoint that is not two finite numbers, too many or none).
std::string ReadWaypointPath(const std::string& path, WaypointPath* out);
// Written atomically.
std::string WriteWaypointPath(const std::string& path, const WaypointPath& waypoints);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_PATH_FILE_H_
