// Running SLAM on a simulated drive and scoring it against ground truth: the scans are recorded
// once per seed so both lattices see exactly the same data.
#ifndef HEX_SLAM_SIM_SCENARIO_RUN_H_
#define HEX_SLAM_SIM_SCENARIO_RUN_H_

#include <cstdint>
#include <vector>

#include "hex_slam/sensor/laser_scan.h"
#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/odometry_model.h"
#include "hex_slam/sim/scenario.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace sim {

struct RecordedDrive {
  std::vector<LaserScan> scans;
  std::vector<Pose2> truth;     // in the map frame, one per scan
  std::vector<Pose2> odometry;  // drifting odometry, one per scan (starts at truth.front())
};

// Scans with the scenario's lidar noise and odometry with `odometry_noise`, all from `seed`.
RecordedDrive RecordDrive(const Scenario& scenario, std::uint64_t seed,
                          const OdometryNoise& odometry_noise = OdometryNoise());

struct SlamRun {
  // The estimate of each scan: with loop closure the optimised one (each scan's front-end pose
  // moved with the last node before it, after the final optimisation), else the front end's.
  std::vector<Pose2> poses;
  std::vector<Pose2> front_end_poses;  // the front end's own, after each scan
  std::vector<double> scan_seconds;  // wall time of each ProcessScan
  double finish_seconds = 0.0;       // with loop closure: the wait for the back end at the end
  int matched = 0;                   // scans that were matched (not skipped or rejected)
};

// Resets `slam` at the first true pose and feeds it every scan (with the odometry if asked);
// with loop closure, then finishes the trajectory and redraws the global map.
SlamRun RunSlam(const RecordedDrive& drive, bool use_odometry, Slam* slam);

struct TrajectoryError {
  double position_rmse = 0.0;  // m
  double position_max = 0.0;   // m
  double angle_rmse = 0.0;     // rad
  double angle_max = 0.0;      // rad
  int poses = 0;
};

// Pose by pose; the two must have the same length (throws std::invalid_argument otherwise).
TrajectoryError CompareTrajectories(const std::vector<Pose2>& estimate,
                                    const std::vector<Pose2>& truth);

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_SCENARIO_RUN_H_
