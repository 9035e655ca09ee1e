// Runs the SLAM processor over a whole log as fast as the CPU allows: the core of
// hex_slam_offline, kept apart from file handling so tests can run it on slices of real logs.
// Scans go in recording order; stamps that go backwards are lowered for the processor only
// (stamp_order.h) while the trajectory keeps the log's own stamps.
#ifndef HEX_SLAM_LOGS_OFFLINE_OFFLINE_RUNNER_H_
#define HEX_SLAM_LOGS_OFFLINE_OFFLINE_RUNNER_H_

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/logs/log_scan.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace logs {

struct OfflineOptions {
  bool use_odometry = true;          // pass the log's odometry to the processor as its prior
  std::optional<Pose2> sensor_pose;  // replaces the log's laser mounting
  // > 0: each scan is handed over no sooner than its stamp (from the first) over `pace`, as a
  // bag played live at that rate reaches the node; the loop-closure worker then runs between
  // scans as it does there. 0: as fast as the CPU allows.
  double pace = 0.0;
};

struct OfflineRun {
  // One pose per scan: log order, log stamps. With loop closure the optimised poses (each scan's
  // front-end pose moved with the last node before it); otherwise the front end's.
  std::vector<io::StampedPose> trajectory;
  std::vector<io::StampedPose> front_end_trajectory;  // the front end's own (local) estimate
  std::vector<double> scan_ms;              // processing time of each scan (front end)
  // The scan path's own CPU time in each scan: scan_ms less the time other threads held its
  // core (a busy machine, or the loop-closure worker beside it on too few cores).
  std::vector<double> scan_cpu_ms;
  // Paced runs only (OfflineOptions::pace > 0): from each scan's arrival (its due time) to its
  // pose, as the node measures it: the pose comes before the scan goes into the map, and a scan
  // that arrives while the one before it is still being inserted waits for it.
  std::vector<double> pose_latency_ms;
  std::map<ScanOutcome, int> outcomes;
  std::string first_rejection;  // the message of the first scan the processor did not use
  int stamps_lowered = 0;       // stamps made non-decreasing for the processor
  int recoveries = 0;
  int map_updates = 0;
  int odometry_faults = 0;            // scans whose odometry increment was dropped
  std::map<TrackingState, int> tracking;  // scans by the tracking state after them
  int times_lost = 0;
  int relocalizations = 0;
  int restarts = 0;  // new submaps started after being lost (loop closure)
  std::string first_lost;  // the first loss's scan and reason
  std::string first_odometry_fault;   // the first one's message
  double log_seconds = 0.0;         // the log's span (first to last stamp, in order)
  double processing_seconds = 0.0;  // sum of scan_ms, in s
  // Loop closure: whether it ran, the wait at the end for the worker's last searches and final
  // optimisation (s), the global map's redraw from the nodes at their optimised poses after it
  // (s; the map output's cost, as writing the files, outside RealtimeFactor), and the worker's
  // figures.
  bool loop_closure = false;
  double finish_seconds = 0.0;
  double map_draw_seconds = 0.0;
  mapping::LoopClosureStats loop_closure_stats;

  int count(ScanOutcome outcome) const {
    const auto it = outcomes.find(outcome);
    return it == outcomes.end() ? 0 : it->second;
  }
  // The log's span over the time to process it: every scan, then the wait for the back end (the
  // worker's own time runs beside the scans, on another core).
  double RealtimeFactor() const {
    const double seconds = processing_seconds + finish_seconds;
    return seconds > 0.0 ? log_seconds / seconds : 0.0;
  }
};

// Keeps the first scan and each one stamped at least `interval` seconds after the last kept one
// (a log subsampled in time: large steps between scans).
void KeepScansApart(double interval, std::vector<LogScan>* scans);

// `slam` should be fresh (or Reset); it holds the map afterwards (with loop closure: the trajectory
// finished and the global map redrawn at the optimised poses). `progress`, when given, is
// called after each scan with the scans done and the seconds spent so far.
using ProgressCallback = std::function<void(std::size_t done, double elapsed)>;
OfflineRun RunOffline(const std::vector<LogScan>& scans, const OfflineOptions& options, Slam* slam,
                      const ProgressCallback& progress = ProgressCallback());

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_OFFLINE_OFFLINE_RUNNER_H_
