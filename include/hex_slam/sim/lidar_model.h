// A planar lidar: beam layout, range limits, Gaussian range noise. Produces core LaserScans.
#ifndef HEX_SLAM_SIM_LIDAR_MODEL_H_
#define HEX_SLAM_SIM_LIDAR_MODEL_H_

#include <random>

#include "hex_slam/sensor/laser_scan.h"
#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/world.h"

namespace hex_slam {
namespace sim {

struct LidarModel {
  int beams = 360;
  double field_of_view = 2.0 * M_PI;  // rad; the scan is centred on the sensor's x axis
  double range_min = 0.05;
  double range_max = 12.0;
  double range_noise_stddev = 0.01;  // m
  // A faulty sensor (or a mount, a cable, a person walking alongside): beams without a return
  // read as hits at range_max - max_range_ghost_margin instead of +inf, a ring of false returns
  // that travels with the sensor. Off by default.
  bool max_range_ghosts = false;
  double max_range_ghost_margin = 0.0;  // m below range_max; 0 reads exactly range_max

  // Beam angles for a full circle must not repeat the first beam at +pi.
  double angle_increment() const;
  double angle_min() const { return -0.5 * field_of_view; }
};

// One scan of `world` from `sensor_pose` (the sensor in the world frame). A beam that hits nothing
// within range_max reads +inf (REP-117: no return), or a ghost hit with max_range_ghosts.
LaserScan SimulateScan(const World& world, const Pose2& sensor_pose, const LidarModel& model,
                       double stamp, std::mt19937_64* rng);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_LIDAR_MODEL_H_
