#include "hex_slam/logs/offline/offline_runner.h"

#include <chrono>
#include <thread>
#include <utility>

#include "hex_slam/common/thread_clock.h"
#include "hex_slam/logs/stamp_order.h"

namespace hex_slam {
namespace logs {

void KeepScansApart(double interval, std::vector<LogScan>* scans) {
  std::vector<LogScan> kept;
  for (LogScan& s : *scans) {
    if (kept.empty() || s.scan.stamp - kept.back().scan.stamp >= interval) {
      kept.push_back(std::move(s));
    }
  }
  *scans = std::move(kept);
}

OfflineRun RunOffline(const std::vector<LogScan>& scans, const OfflineOptions& options, Slam* slam,
                      const ProgressCallback& progress) {
  OfflineRun run;
  std::vector<double> stamps, processing_stamps;
  stamps.reserve(scans.size());
  for (const LogScan& s : scans) stamps.push_back(s.scan.stamp);
  run.stamps_lowered = MakeStampsNonDecreasing(stamps, &processing_stamps);
  if (!processing_stamps.empty()) {
    run.log_seconds = processing_stamps.back() - processing_stamps.front();
  }
  run.front_end_trajectory.reserve(scans.size());
  run.scan_ms.reserve(scans.size());
  run.scan_cpu_ms.reserve(scans.size());
  std::vector<int> last_node;  // the newest node at each scan (-1 before the first)
  last_node.reserve(scans.size());
  const auto start = std::chrono::steady_clock::now();
  LaserScan scan;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const LogScan& in = scans[i];
    scan = in.scan;
    scan.stamp = processing_stamps[i];
    const Pose2 sensor_pose = options.sensor_pose ? *options.sensor_pose : in.sensor_pose;
    const std::optional<Pose2> odometry = options.use_odometry ? in.odometry : std::nullopt;
    // Paced as a bag played live, the scan arrives at its due time and goes through the node's
    // order: pose, then map.
    const bool as_node = options.pace > 0.0;
    std::chrono::steady_clock::time_point arrival = start;
    if (as_node) {
      const double due = (processing_stamps[i] - processing_stamps.front()) / options.pace;
      arrival += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(due));
      std::this_thread::sleep_until(arrival);
    }
    const auto before = std::chrono::steady_clock::now();
    const double cpu_before = ThreadCpuSeconds();
    ScanReport report = slam->ProcessScan(scan, SensorMount(sensor_pose), odometry, as_node);
    if (as_node) {
      run.pose_latency_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - arrival)
              .count());
      if (report.map_update_deferred) slam->InsertDeferredScan(&report);
    }
    run.scan_cpu_ms.push_back(1e3 * (ThreadCpuSeconds() - cpu_before));
    const auto after = std::chrono::steady_clock::now();
    run.scan_ms.push_back(std::chrono::duration<double, std::milli>(after - before).count());
    run.processing_seconds += run.scan_ms.back() * 1e-3;
    ++run.outcomes[report.outcome];
    const bool used = report.outcome == ScanOutcome::kMatched ||
                      report.outcome == ScanOutcome::kInitialized ||
                      report.outcome == ScanOutcome::kKnownPose;
    if (!used && run.first_rejection.empty()) {
      run.first_rejection = "scan " + std::to_string(i) + ": " +
                            ScanOutcomeName(report.outcome) + ": " + report.message;
    }
    if (report.odometry_fault && run.odometry_faults++ == 0) {
      run.first_odometry_fault = "scan " + std::to_string(i) + ": " + report.message;
    }
    if (used || report.outcome == ScanOutcome::kTooFewPoints) ++run.tracking[report.tracking_state];
    if (report.tracking_changed && report.tracking_state == TrackingState::kLost &&
        run.first_lost.empty()) {
      run.first_lost = "scan " + std::to_string(i) + ": " + report.tracking_reason;
    }
    run.front_end_trajectory.push_back({in.scan.stamp, report.pose});
    last_node.push_back(report.node_id >= 0 ? report.node_id
                                            : last_node.empty() ? -1 : last_node.back());
    if (progress) progress(i + 1, std::chrono::duration<double>(after - start).count());
  }
  run.recoveries = slam->recoveries();
  run.times_lost = slam->times_lost();
  run.relocalizations = slam->relocalizations();
  run.restarts = slam->restarts();
  run.map_updates = slam->map_updates();
  run.loop_closure = slam->loop_closure_active();
  if (!run.loop_closure) {
    run.trajectory = run.front_end_trajectory;
    return run;
  }
  const auto finish_start = std::chrono::steady_clock::now();
  slam->FinishLoopClosure();
  const auto draw_start = std::chrono::steady_clock::now();
  run.finish_seconds = std::chrono::duration<double>(draw_start - finish_start).count();
  slam->RefreshGlobalMap();
  run.map_draw_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - draw_start).count();
  run.loop_closure_stats = slam->loop_closure_stats();
  const std::shared_ptr<const mapping::PoseGraphSolution> solution = slam->solutions()->Get();
  run.trajectory.reserve(scans.size());
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const io::StampedPose& local = run.front_end_trajectory[i];
    run.trajectory.push_back({local.stamp, solution->ToGlobal(local.pose, last_node[i])});
  }
  return run;
}

}  // namespace logs
}  // namespace hex_slam
