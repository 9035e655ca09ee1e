// Maps of the synthetic test room built from noise-free scans at known poses, for matcher tests.
#ifndef HEX_SLAM_TEST_CORE_TEST_MAPS_H_
#define HEX_SLAM_TEST_CORE_TEST_MAPS_H_

#include <random>
#include <vector>

#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/sensor/scan_sanitizer.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/sim/segment_world.h"

namespace hex_slam {
namespace testing_util {

// The test room placed off the lattice's symmetry lines (see sim/room_drive.h). With every wall on
// a row of cell centres the map's quantisation biases all walls the same way and the static
// matching bias reaches d/4; at a generic placement it averages out (~1.5 mm at d = 5 cm for
// either lattice), which is what a real building looks like to a robot.
inline const Pose2& GenericPlacement() { return sim::GenericRoomPlacement(); }
inline sim::SegmentWorld GenericRoom() {
  return sim::SegmentWorld::TestRoom().Transformed(GenericPlacement());
}

inline std::vector<Eigen::Vector2d> ScanPoints(const sim::World& world, const Pose2& pose,
                                               const sim::LidarModel& lidar,
                                               std::mt19937_64* rng) {
  const LaserScan scan = sim::SimulateScan(world, pose, lidar, 0.0, rng);
  std::vector<Eigen::Vector2d> points;
  BeamCounts counts;
  std::string message;
  SanitizeScan(scan, RangeFilter{}, &points, &counts, &message);
  return points;
}

// A pyramid mapped from scans at a handful of poses spread over the generic room.
template <class Lattice>
MapPyramid<Lattice> MapOfTestRoom(double spacing, int levels = 3) {
  const sim::SegmentWorld world = GenericRoom();
  sim::LidarModel lidar;
  lidar.beams = 720;
  lidar.range_noise_stddev = 0.0;
  MapPyramid<Lattice> maps(spacing, levels, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                           GridGrowthPolicy(),
                           Eigen::AlignedBox2d(Eigen::Vector2d(-6, -5), Eigen::Vector2d(6, 5)));
  std::mt19937_64 rng(0);
  for (const Pose2& room_pose : {Pose2(0, 0, 0), Pose2(-2.5, 1.0, 0.3), Pose2(3.2, -0.5, -1.0),
                            Pose2(-3.5, -2.0, 2.0), Pose2(2.5, 3.0, 0.7)}) {
    const Pose2 pose = GenericPlacement() * room_pose;
    std::vector<Eigen::Vector2d> world_points;
    for (const auto& p : ScanPoints(world, pose, lidar, &rng)) world_points.push_back(pose * p);
    for (int repeat = 0; repeat < 3; ++repeat) maps.InsertScan(pose.translation(), world_points);
  }
  return maps;
}

// A room whose walls all sit 3 cm past a row of centres of a 0.1 m square lattice, on the same
// side: the plain square map puts every wall at its cells' centres, so the static matching bias
// is the same 3 cm along x and y for every pose (sqrt(2)·3 cm); the hex lattice's phases vary.
inline sim::SegmentWorld BiasedRoom() {
  sim::SegmentWorld w;
  w.AddRectangle({-1.97, -1.47}, {2.03, 1.53});
  w.AddRectangle({0.53, -0.47}, {0.93, -0.07});
  w.AddRectangle({-1.07, 0.33}, {-0.77, 0.73});
  return w;
}

// The mean position error of matches started at the true pose in BiasedRoom (mapped with 1 cm
// range noise from five poses), over 30 random poses: the matcher's static bias.
template <class Lattice, class Matcher>
double StaticBiasInBiasedRoom(double spacing, const ScanMatcherOptions& options) {
  const sim::SegmentWorld world = BiasedRoom();
  sim::LidarModel lidar;
  lidar.beams = 720;
  MapPyramid<Lattice> maps(spacing, 3, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                           GridGrowthPolicy(),
                           Eigen::AlignedBox2d(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3)));
  std::mt19937_64 rng(1);
  for (const Pose2& pose : {Pose2(0, 0, 0), Pose2(-1.2, 0.9, 0.3), Pose2(1.4, 0.8, -1.0),
                            Pose2(-1.0, -0.9, 2.0), Pose2(1.5, -1.0, 0.7)}) {
    std::vector<Eigen::Vector2d> world_points;
    for (const auto& p : ScanPoints(world, pose, lidar, &rng)) world_points.push_back(pose * p);
    for (int repeat = 0; repeat < 3; ++repeat) maps.InsertScan(pose.translation(), world_points);
  }
  lidar.range_noise_stddev = 0.0;
  const Matcher matcher(options);
  std::uniform_real_distribution<double> ux(-1.3, 1.5), uy(-1.0, 1.0), heading(-M_PI, M_PI);
  double sum = 0.0;
  const int poses = 30;
  for (int i = 0; i < poses; ++i) {
    const Pose2 truth(ux(rng), uy(rng), heading(rng));
    const MatchResult result = matcher.Match(maps, ScanPoints(world, truth, lidar, &rng), truth);
    sum += (result.pose.translation() - truth.translation()).norm();
  }
  return sum / poses;
}

}  // namespace testing_util
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_CORE_TEST_MAPS_H_
