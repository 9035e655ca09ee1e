#include "hex_slam/sim/room_drive.h"

#include <cmath>

namespace hex_slam {
namespace sim {

const Pose2& GenericRoomPlacement() {
  static const Pose2 placement(0.013, 0.029, 0.3);
  return placement;
}

RoomDrive MakeRoomDrive(int beams, double range_noise_stddev, const PathMotion& motion) {
  const Pose2& placement = GenericRoomPlacement();
  RoomDrive drive;
  drive.world = SegmentWorld::TestRoom().Transformed(placement);
  // Through both halves of the room and its door, round the boxes, back to the start.
  std::vector<Eigen::Vector2d> loop = {
      {0.0, -0.4}, {3.0, -0.4}, {2.5, 1.8},  {2.5, 3.3},  {-3.0, 3.3}, {-3.0, 0.0},
      {-3.5, -1.0}, {-3.5, -2.8}, {-1.0, -3.0}, {0.5, -3.0}, {0.5, -0.4}, {0.0, -0.4}};
  for (Eigen::Vector2d& p : loop) p = placement * p;
  drive.truth = SampleWaypointPath(loop, placement.theta, motion);
  drive.scan_period = 1.0 / motion.rate;
  drive.lidar.beams = beams;
  if (beams == 1081) {
    drive.lidar.field_of_view = 270.0 * M_PI / 180.0;
    drive.lidar.range_max = 30.0;
  } else {
    drive.lidar.field_of_view = 2.0 * M_PI;
    drive.lidar.range_max = 12.0;
  }
  drive.lidar.range_noise_stddev = range_noise_stddev;
  return drive;
}

}  // namespace sim
}  // namespace hex_slam
