#include "node_diagnostics.h"

#include <cstdio>
#include <vector>

#include <diagnostic_msgs/KeyValue.h>

namespace hex_slam {
namespace node {
namespace {

diagnostic_msgs::KeyValue Value(const std::string& key, double value) {
  diagnostic_msgs::KeyValue kv;
  kv.key = key;
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  kv.value = text;
  return kv;
}

diagnostic_msgs::KeyValue Value(const std::string& key, long value) {
  diagnostic_msgs::KeyValue kv;
  kv.key = key;
  kv.value = std::to_string(value);
  return kv;
}

diagnostic_msgs::KeyValue Text(const std::string& key, const std::string& value) {
  diagnostic_msgs::KeyValue kv;
  kv.key = key;
  kv.value = value;
  return kv;
}

}  // namespace

diagnostic_msgs::DiagnosticStatus MakeDiagnostics(const std::string& name, const ScanStats& scans,
                                                  const MapStats& map, long previous_drops) {
  constexpr double kBytesPerMegabyte = 1024.0 * 1024.0;
  diagnostic_msgs::DiagnosticStatus status;
  status.name = name;
  const DropCounters& d = scans.drops;
  const bool dropping = d.total() > previous_drops;
  const TrackingStats& k = scans.tracking;
  const bool lost = k.state == "lost", degraded = k.state == "degraded";
  status.level = lost                    ? diagnostic_msgs::DiagnosticStatus::ERROR
                 : degraded || dropping ? diagnostic_msgs::DiagnosticStatus::WARN
                                        : diagnostic_msgs::DiagnosticStatus::OK;
  status.message = map.paused          ? "paused"
                   : lost || degraded ? "tracking " + k.state + ": " + k.reason
                   : dropping          ? "dropping scans"
                                       : "mapping";
  const TimingStats& t = scans.timing;
  status.values = {
      Text("tracking_state", k.state),
      Text("tracking_reason", k.reason),
      Value("match_score", k.match_score),
      Value("sigma_x_m", k.sigma_x),
      Value("sigma_y_m", k.sigma_y),
      Value("sigma_yaw_rad", k.sigma_yaw),
      Value("scans_ok", k.scans_ok),
      Value("scans_degraded", k.scans_degraded),
      Value("scans_lost", k.scans_lost),
      Value("times_lost", k.times_lost),
      Value("relocalizations", k.relocalizations),
      Value("restarts_after_lost", k.restarts),
      Value("scans_matched", t.count()),
      Value("scans_processed_by_core", static_cast<long>(map.scans_processed)),
      Value("map_updates", static_cast<long>(map.map_updates)),
      Value("recoveries", static_cast<long>(map.recoveries)),
      Value("map_levels", static_cast<long>(map.levels)),
      Value("callback_mean_ms", t.callback_mean()),
      Value("core_mean_ms", t.core_mean()),
      Value("overhead_mean_ms", t.overhead_mean()),
      Value("callback_max_ms", t.callback_max()),
      Value("overhead_max_ms", t.overhead_max()),
      Value("latency_p50_ms", t.latency().Quantile(0.5)),
      Value("latency_p99_ms", t.latency().Quantile(0.99)),
      Value("latency_max_ms", t.latency().max()),
      Value("dropped_no_laser_transform", d.no_laser_transform),
      Value("dropped_invalid", d.invalid),
      Value("dropped_late", d.late),
      Value("dropped_paused", d.paused),
      Value("errors", d.errors),
      Value("dropped_queue_overflow", d.queue_overflow),
      Value("no_odometry", scans.no_odometry),
      Value("time_jump_resets", scans.time_jump_resets),
      Value("map_memory_mb", map.memory_bytes / kBytesPerMegabyte),
      Value("peak_resident_mb", map.peak_resident_mb),
      Value("snapshot_ms", map.snapshot_ms),
      Value("snapshot_ms_max", map.snapshot_ms_max),
      Value("raster_ms", map.raster_ms),
  };
  if (map.global.searches > 0) {
    const mapping::GlobalLocalizationStats& g = map.global;
    const std::vector<diagnostic_msgs::KeyValue> global = {
        Value("global_searches", static_cast<long>(g.searches)),
        Value("global_searches_ambiguous", static_cast<long>(g.ambiguous)),
        Value("global_relocalizations", static_cast<long>(g.accepted)),
        Value("global_search_max_ms", g.max_seconds * 1e3),
    };
    status.values.insert(status.values.end(), global.begin(), global.end());
  }
  if (map.loop_closure) {
    const mapping::LoopClosureStats& l = map.loop;
    const long found = l.search.local_found + l.search.global_found;
    const std::vector<diagnostic_msgs::KeyValue> loop = {
        Value("loop_nodes", static_cast<long>(l.nodes)),
        Value("loop_submaps", static_cast<long>(l.submaps)),
        Value("loop_searches", l.search.local_searches + l.search.global_searches),
        Value("loop_constraints_found", found),
        Value("loop_constraints_ambiguous", l.search.ambiguous),
        Value("loop_global_candidates_confirmed", static_cast<long>(l.global_confirmed)),
        Value("loop_global_candidates_dropped", static_cast<long>(l.global_unconfirmed)),
        Value("loop_global_candidates_rivals", static_cast<long>(l.global_rivals)),
        Value("loop_constraints_accepted", static_cast<long>(l.loop_constraints_consistent)),
        Value("loop_optimizations", static_cast<long>(l.optimizations)),
        Value("loop_last_optimization_ms", l.last_optimization_seconds * 1e3),
        Value("loop_worker_busy_s", l.busy_seconds),
        Value("loop_worker_cpu_s", l.cpu_seconds),
        Value("loop_worker_queued", static_cast<long>(l.queued)),
        Value("loop_worker_max_queued", static_cast<long>(l.max_queued)),
        Value("loop_worker_submaps_queued_without_grids", l.pyramids_not_queued),
        Value("map_redraws", static_cast<long>(map.map_redraws)),
        Value("map_redraw_ms", map.map_redraw_ms),
        Value("map_solution_version", static_cast<long>(map.map_solution_version)),
    };
    status.values.insert(status.values.end(), loop.begin(), loop.end());
    if (!l.first_error.empty() && status.level == diagnostic_msgs::DiagnosticStatus::OK) {
      status.level = diagnostic_msgs::DiagnosticStatus::WARN;
      status.message = "loop closure: " + l.first_error;
    }
  }
  return status;
}

}  // namespace node
}  // namespace hex_slam
