// What the node counts about its scans, and the diagnostic_msgs status it publishes on
// /diagnostics (shown by rqt_runtime_monitor, read by the rostests): scans matched and dropped
// by reason, the callback's cost against the core's, the map's size.
#ifndef HEX_SLAM_NODE_NODE_DIAGNOSTICS_H_
#define HEX_SLAM_NODE_NODE_DIAGNOSTICS_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include <diagnostic_msgs/DiagnosticStatus.h>

#include "hex_slam/mapping/global_localizer.h"
#include "hex_slam/mapping/loop_closure/loop_closure_worker.h"
#include "timing_stats.h"

namespace hex_slam {
namespace node {

// Scans the node did not match, by reason (each also logged, throttled).
struct DropCounters {
  long no_laser_transform = 0;  // tf could not place the scan's frame on the base
  long invalid = 0;             // malformed: NaN limits, bad increment, size mismatch, ...
  long late = 0;                // stamped slightly before the previous scan
  long paused = 0;              // pause_mapping was on
  long errors = 0;              // the core threw (out of memory, ...)
  long queue_overflow = 0;      // the node fell behind: the oldest waiting scan made room
  long total() const {
    return no_laser_transform + invalid + late + paused + errors + queue_overflow;
  }
};

// The tracking state (hex_slam/mapping/tracking_state.h) after the latest scan, and how often each
// state was seen.
struct TrackingStats {
  std::string state = "ok";  // TrackingStateName
  std::string reason;        // why it is what it is
  double match_score = 0.0;  // the latest scored match's agreement with the map (0..1)
  double sigma_x = 0.0, sigma_y = 0.0, sigma_yaw = 0.0;  // the latest published covariance's
  long scans_ok = 0, scans_degraded = 0, scans_lost = 0;
  long times_lost = 0;
  long relocalizations = 0;
  long restarts = 0;  // new submaps started after being lost (loop closure, odometry)
};

struct ScanStats {
  DropCounters drops;
  TimingStats timing;      // scans that reached the core and were published
  long no_odometry = 0;    // matched, but without the odometry prior
  long time_jump_resets = 0;  // map resets because the stamps jumped back
  TrackingStats tracking;
};

// The core's side, read under the SLAM lock.
struct MapStats {
  int scans_processed = 0;
  int map_updates = 0;
  int recoveries = 0;
  int levels = 0;  // pyramid levels built
  std::size_t memory_bytes = 0;
  bool paused = false;
  // The map thread's latest work: copying the snapshot holds the SLAM lock (a scan may wait
  // that long), rasterising it does not.
  double snapshot_ms = 0.0;
  double snapshot_ms_max = 0.0;
  double raster_ms = 0.0;
  double peak_resident_mb = 0.0;  // the whole process's peak resident memory
  bool loop_closure = false;  // the back end runs: `loop` holds its worker's figures
  mapping::LoopClosureStats loop;
  // With loop closure: the map outputs' redraws from the nodes at a new solution, the latest's
  // time, and the solution they show.
  int map_redraws = 0;
  double map_redraw_ms = 0.0;
  std::uint64_t map_solution_version = 0;
  // On a loaded map with update_map false: the searches over the whole map (global_localization).
  mapping::GlobalLocalizationStats global;
};

// ERROR while lost, WARN while degraded or while scans are being dropped (more drops than at
// `previous_drops`), else OK; the message says which.
diagnostic_msgs::DiagnosticStatus MakeDiagnostics(const std::string& name, const ScanStats& scans,
                                                  const MapStats& map, long previous_drops);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_NODE_DIAGNOSTICS_H_
