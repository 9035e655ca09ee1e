// A building-sized world for loop closure: a 60 m × 32 m office floor with a 2.4 m corridor
// running round a block of rooms, rooms on both sides behind doors at irregular spacing, cabinets
// and furniture (so no stretch of corridor is a copy of another). The drive goes round the
// corridor twice, 280 m; the lidar is a 5 Hz SICK-like scanner (361 beams over 180°, 30 m), so
// the long corridors leave its matching little to hold on to along their axis, and the drift of
// the first lap is what the second lap's loop closures must remove.
#ifndef HEX_SLAM_SIM_BUILDING_LOOP_H_
#define HEX_SLAM_SIM_BUILDING_LOOP_H_

#include <cstdint>
#include <vector>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/odometry_model.h"
#include "hex_slam/sim/scenario_run.h"
#include "hex_slam/sim/segment_world.h"
#include "hex_slam/sim/waypoint_path.h"

namespace hex_slam {
namespace sim {

struct BuildingLoop {
  SegmentWorld world;
  std::vector<Pose2> truth;  // the robot (and its lidar) at each scan
  LidarModel lidar;
  double scan_period = 0.2;  // s
};

// `laps` times round the corridor (the last lap ends where the first began).
BuildingLoop MakeBuildingLoop(int laps = 2);

// Scans of the drive with the lidar's noise, and odometry drifting by `odometry_noise`, from
// `seed`.
RecordedDrive RecordBuildingLoop(const BuildingLoop& loop, std::uint64_t seed,
                                 const OdometryNoise& odometry_noise);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_BUILDING_LOOP_H_
