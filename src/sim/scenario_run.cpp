#include "hex_slam/sim/scenario_run.h"

#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

namespace hex_slam {
namespace sim {
namespace {

// The odometry's random stream is derived from the seed but differs from the lidar's.
constexpr std::uint64_t kOdometrySeedOffset = 0x9e3779b97f4a7c15ULL;

}  // namespace

RecordedDrive RecordDrive(const Scenario& scenario, std::uint64_t seed,
                          const OdometryNoise& odometry_noise) {
  RecordedDrive drive;
  drive.truth = scenario.truth;
  if (drive.truth.empty()) return drive;
  const PlacedWorld world = scenario.World();
  std::mt19937_64 rng(seed);
  DriftingOdometry odometry(odometry_noise, seed + kOdometrySeedOffset, drive.truth.front());
  drive.scans.reserve(drive.truth.size());
  drive.odometry.reserve(drive.truth.size());
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    drive.scans.push_back(
        SimulateScan(world, drive.truth[i], scenario.lidar, scenario.scan_period * i, &rng));
    drive.odometry.push_back(odometry.Update(drive.truth[i]));
  }
  return drive;
}

SlamRun RunSlam(const RecordedDrive& drive, bool use_odometry, Slam* slam) {
  SlamRun run;
  if (drive.truth.empty()) return run;
  slam->Reset(drive.truth.front());
  run.front_end_poses.reserve(drive.scans.size());
  run.scan_seconds.reserve(drive.scans.size());
  std::vector<int> last_node;  // the newest node at each scan (-1 before the first)
  for (std::size_t i = 0; i < drive.scans.size(); ++i) {
    const auto start = std::chrono::steady_clock::now();
    const ScanReport report =
        use_odometry ? slam->ProcessScan(drive.scans[i], Pose2(), drive.odometry[i])
                     : slam->ProcessScan(drive.scans[i]);
    run.scan_seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    run.front_end_poses.push_back(report.pose);
    last_node.push_back(report.node_id >= 0 ? report.node_id
                                            : last_node.empty() ? -1 : last_node.back());
    if (report.outcome == ScanOutcome::kMatched) ++run.matched;
  }
  if (!slam->loop_closure_active()) {
    run.poses = run.front_end_poses;
    return run;
  }
  const auto start = std::chrono::steady_clock::now();
  slam->FinishTrajectory();
  run.finish_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto solution = slam->solutions()->Get();
  for (std::size_t i = 0; i < run.front_end_poses.size(); ++i) {
    run.poses.push_back(solution->ToGlobal(run.front_end_poses[i], last_node[i]));
  }
  return run;
}

TrajectoryError CompareTrajectories(const std::vector<Pose2>& estimate,
                                    const std::vector<Pose2>& truth) {
  if (estimate.size() != truth.size()) {
    throw std::invalid_argument("CompareTrajectories: trajectories differ in length");
  }
  TrajectoryError error;
  error.poses = static_cast<int>(truth.size());
  if (truth.empty()) return error;
  double sum_sq = 0.0, sum_sq_angle = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double e = (estimate[i].translation() - truth[i].translation()).norm();
    const double a = std::abs(NormalizeAngle(estimate[i].theta - truth[i].theta));
    sum_sq += e * e;
    sum_sq_angle += a * a;
    error.position_max = std::max(error.position_max, e);
    error.angle_max = std::max(error.angle_max, a);
  }
  error.position_rmse = std::sqrt(sum_sq / truth.size());
  error.angle_rmse = std::sqrt(sum_sq_angle / truth.size());
  return error;
}

}  // namespace sim
}  // namespace hex_slam
