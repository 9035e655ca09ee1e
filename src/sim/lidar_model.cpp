#include "hex_slam/sim/lidar_model.h"

#include <cmath>
#include <limits>

namespace hex_slam {
namespace sim {

double LidarModel::angle_increment() const {
  const bool full_circle = field_of_view >= 2.0 * M_PI - 1e-9;
  return full_circle ? field_of_view / beams : field_of_view / std::max(1, beams - 1);
}

LaserScan SimulateScan(const World& world, const Pose2& sensor_pose, const LidarModel& model,
                       double stamp, std::mt19937_64* rng) {
  LaserScan scan;
  scan.stamp = stamp;
  scan.angle_min = model.angle_min();
  scan.angle_increment = model.angle_increment();
  scan.angle_max = scan.angle_min + (model.beams - 1) * scan.angle_increment;
  scan.range_min = model.range_min;
  scan.range_max = model.range_max;
  scan.ranges.resize(model.beams);
  std::normal_distribution<double> noise(0.0, model.range_noise_stddev);
  for (int i = 0; i < model.beams; ++i) {
    const double angle = sensor_pose.theta + scan.angle_min + i * scan.angle_increment;
    double r = world.CastRay(sensor_pose.translation(), angle, model.range_max);
    if (std::isfinite(r) && model.range_noise_stddev > 0.0) r += noise(*rng);
    if (std::isfinite(r) && r < model.range_min) r = -std::numeric_limits<double>::infinity();
    if (model.max_range_ghosts && r == std::numeric_limits<double>::infinity()) {
      r = model.range_max - model.max_range_ghost_margin;
    }
    scan.ranges[i] = static_cast<float>(r);
  }
  return scan;
}

}  // namespace sim
}  // namespace hex_slam
