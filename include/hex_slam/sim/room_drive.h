// The built-in synthetic scenario: a loop through the test room (SegmentWorld::TestRoom) placed
// off the lattice's symmetry lines, with the ground-truth poses and a lidar model.
#ifndef HEX_SLAM_SIM_ROOM_DRIVE_H_
#define HEX_SLAM_SIM_ROOM_DRIVE_H_

#include <vector>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/segment_world.h"
#include "hex_slam/sim/waypoint_path.h"

namespace hex_slam {
namespace sim {

struct RoomDrive {
  SegmentWorld world;
  std::vector<Pose2> truth;  // the robot (and sensor) pose at each scan
  LidarModel lidar;
  double scan_period = 0.1;  // s
};

// The room rotated and shifted so no wall lies on a row of cell centres: an aligned room biases
// every wall the same way (the static matching bias reaches d/4), a generic one does not.
const Pose2& GenericRoomPlacement();

// `beams` 1081 gives a Hokuyo UTM-30LX (270°, 30 m); anything else a 360° 12 m RPLidar-like scan.
RoomDrive MakeRoomDrive(int beams, double range_noise_stddev = 0.01,
                        const PathMotion& motion = PathMotion());

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_ROOM_DRIVE_H_
