// hex_slam_offline: the SLAM core over a recorded log, as fast as the CPU allows. Reads a ROS bag
// or a CARMEN log, runs every scan through hex_slam::Slam, writes the trajectory and the maps,
// and ends with one RESULT line of timing figures. The same YAML parameter file as the node.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "hex_slam/common/heap_retention.h"
#include "hex_slam/common/input_limits.h"
#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/io/parameter_file.h"
#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/logs/bag_reader.h"
#include "hex_slam/logs/carmen_reader.h"
#include "hex_slam/logs/evaluation/map_consistency.h"
#include "hex_slam/logs/offline/offline_config.h"
#include "hex_slam/logs/offline/offline_runner.h"
#include "hex_slam/logs/offline/progress_bar.h"
#include "hex_slam/logs/offline/resource_usage.h"
#include "hex_slam/logs/offline/run_outputs.h"
#include "hex_slam/logs/evaluation/sample_statistics.h"
#include "command_line.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

struct Args {
  std::string bag;
  std::string carmen;
  std::string topic;       // empty: scan_topic from the parameters
  std::string odom_topic;  // empty: the bag's only Odometry topic
  std::string laser;       // CARMEN laser message; empty: the first one
  std::string config;
  std::map<std::string, std::string> overrides;  // --set, --lattice, --no-odom
  std::optional<Pose2> sensor_pose;
  std::string map;                    // a .hexmap to start from (localization: update_map false)
  std::optional<Pose2> initial_pose;  // the robot's pose on that map at the first scan
  std::string out;
  long max_scans = -1;
  double min_scan_interval = 0.0;  // s; 0 keeps every scan
  double pace = 0.0;               // the log played live at this rate; 0: as fast as possible
  bool skip_bad_lines = false;
  bool progress = true;
};

// The command line; the checks that span options come after parsing (CheckArgs).
void Declare(CLI::App* app, Args* args) {
  app->description(
      "Runs hex_slam over a ROS bag (laser mounting and odometry from its tf, or an Odometry "
      "topic) or a CARMEN log (FLASER, ROBOTLASER1, RAWLASER1-4 with ODOM), as fast as the CPU "
      "allows.");
  app->footer(
      "Ends with: RESULT scans=... mean_ms=... median_ms=... p99_ms=... realtime_factor=... "
      "peak_rss_mb=... (realtime_factor: the log's span over the scans' time plus the wait for "
      "the loop-closure back end at the end; map_draw_s, the map's redraw at the optimised poses "
      "after it, is output as writing the files is, and not counted)");
  const auto text = [app](const std::string& name, std::string* value, const std::string& what) {
    return app->add_option(name, *value, what)->check(cli::NonEmpty());
  };
  text("--bag", &args->bag, "a ROS bag (give it or --carmen)");
  text("--topic", &args->topic, "the bag's scan topic (default: scan_topic from the parameters)");
  text("--odom-topic", &args->odom_topic, "the bag's Odometry topic (default: its only one)");
  text("--carmen", &args->carmen, "a CARMEN log (give it or --bag)");
  text("--laser", &args->laser, "the CARMEN laser message (default: the first one)");
  text("--config", &args->config, "the node's flat YAML parameter file");
  cli::AddSettings(app, "--set", &args->overrides, "overrides one parameter");
  app->add_option_function<std::string>(
         "--lattice", [args](const std::string& v) { args->overrides["lattice"] = v; },
         "hex or square")
      ->check(cli::NonEmpty());
  app->add_flag_callback("--no-odom", [args] { args->overrides["use_odometry"] = "false"; },
                         "match without odometry");
  app->add_flag_callback(
      "--no-loop-closure", [args] { args->overrides["loop_closure"] = "false"; },
      "one map and no back end (hector's way); loop closure is on by default, as in the node's "
      "config/default.yaml");
  cli::AddOptionalPose(app, "--sensor-pose", &args->sensor_pose,
                       "the laser in the base frame (default: from tf; identity in a bag "
                       "without tf)",
                       CheckSensorPose);
  text("--map", &args->map,
       "starts from a saved map (with --set update_map=false: localization only)");
  cli::AddOptionalPose(app, "--initial-pose", &args->initial_pose,
                       "the robot on --map (default 0,0,0), within laser_max_dist of its known "
                       "cells",
                       CheckPose);
  text("--out", &args->out,
       "writes trajectory.tum (with loop closure the optimised poses, and "
       "front_end_trajectory.tum the front end's own), map.pgm + map.yaml, map.hexmap, "
       "hex_map.png and trajectory.png");
  app->add_option("--max-scans", args->max_scans, "reads no more scans than this")
      ->check(cli::NonNegative());
  cli::AddNumber(app, "--min-scan-interval", &args->min_scan_interval,
                 "keeps a scan only this many seconds or more after the last kept one (a "
                 "subsampled log: large steps between scans)",
                 0.0);
  cli::AddNumber(app, "--pace", &args->pace,
                 "hands each scan over at this multiple of the log's rate, as a bag played "
                 "live reaches the node (whose loop-closure worker settings it then takes "
                 "unless set: niceness 10, no wait for the worker): the scan path's latency "
                 "as in the node; 0 (default): as fast as the CPU allows",
                 0.0);
  app->add_flag("--skip-bad-lines", args->skip_bad_lines,
                "skips and counts malformed CARMEN lines or bag messages instead of stopping at "
                "the first, named");
  app->add_flag_callback("--no-progress", [args] { args->progress = false; },
                         "no progress bar on stderr");
}

// Empty, or what is wrong with the options taken together.
std::string CheckArgs(const Args& args) {
  if (args.bag.empty() == args.carmen.empty()) return "give exactly one of --bag and --carmen";
  if (args.initial_pose && args.map.empty()) return "--initial-pose places the robot on a --map";
  return "";
}

void PrintLoopClosure(const logs::OfflineRun& run) {
  const mapping::LoopClosureStats& lc = run.loop_closure_stats;
  const mapping::ConstraintSearchStats& search = lc.search;
  std::printf("loop closure: %d nodes in %d submaps; %ld local searches found %ld constraints, "
              "%ld global searches found %ld (%d confirmed by a later node, %d not, %d refused as "
              "rivals), %ld ambiguous matches refused; %d loop constraints, %d consistent with "
              "the final solution (%d nodes found slipped and solved again)\n",
              lc.nodes, lc.submaps, search.local_searches, search.local_found,
              search.global_searches, search.global_found, lc.global_confirmed,
              lc.global_unconfirmed, lc.global_rivals, search.ambiguous, lc.loop_constraints,
              lc.loop_constraints_consistent, lc.slipped_nodes);
  std::printf("  background: %.3f s busy, %.3f s of it on a core (%.3f ms per node; searches "
              "%.3f s; %ld search grids built, %ld submaps redrawn, at most %.0f MB held), "
              "%d optimisations %.3f s (%.1f ms each, last %.1f ms); at most %zu jobs queued (%ld "
              "submaps without their grids); "
              "%.2f s waited for it at the end, the map redrawn at the optimised poses in %.2f s\n",
              lc.busy_seconds, lc.cpu_seconds,
              lc.nodes > 0 ? 1e3 * lc.cpu_seconds / lc.nodes : 0.0, search.search_seconds,
              lc.search_grids_built, lc.submaps_redrawn,
              lc.cached_submap_bytes / 1e6, lc.optimizations,
              lc.optimization_seconds,
              lc.optimizations > 0 ? 1e3 * lc.optimization_seconds / lc.optimizations : 0.0,
              1e3 * lc.last_optimization_seconds, lc.max_queued, lc.pyramids_not_queued,
              run.finish_seconds,
              run.map_draw_seconds);
  if (!lc.first_error.empty()) std::printf("  a job failed: %s\n", lc.first_error.c_str());
}

// Parameters: defaults, then the file, then the command line.
bool Configure(const Args& args, logs::OfflineConfig* config) {
  std::map<std::string, std::string> values;
  if (!args.config.empty()) {
    const std::string error = io::ReadParameterFile(args.config, &values);
    if (!error.empty()) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return false;
    }
  }
  for (const auto& [key, value] : args.overrides) values[key] = value;
  if (args.pace > 0.0) {
    // Played live, the run stands for the node: its worker steps back from the scan path, which
    // never waits for it (unless a file or --set says otherwise).
    const mapping::LoopClosureOptions node;
    values.emplace("loop_closure_worker_niceness", std::to_string(node.worker_niceness));
    values.emplace("loop_closure_max_queued_submaps", std::to_string(node.max_queued_submaps));
  }
  std::vector<std::string> ignored;
  std::vector<std::string> errors = logs::ApplyOfflineParameters(values, config, &ignored);
  for (const std::string& e : config->slam.Validate()) errors.push_back(e);
  for (const std::string& e : errors) std::fprintf(stderr, "error: %s\n", e.c_str());
  if (!ignored.empty()) {
    std::string list;
    for (const std::string& k : ignored) list += " " + k;
    std::printf("ignored (ROS interface only):%s\n", list.c_str());
  }
  return errors.empty();
}

bool ReadLog(const Args& args, const logs::OfflineConfig& config, std::vector<logs::LogScan>* scans) {
  std::string error;
  if (!args.carmen.empty()) {
    logs::CarmenReadOptions options;
    options.laser_message = args.laser;
    options.skip_bad_lines = args.skip_bad_lines;
    logs::CarmenLog log;
    error = logs::ReadCarmenLog(args.carmen, options, &log);
    if (error.empty()) {
      std::printf("%s: %zu %s scans, %d ODOM lines, %d other lines", args.carmen.c_str(),
                  log.scans.size(), log.laser_message.c_str(), log.odometry_lines, log.other_lines);
      if (log.bad_lines > 0) std::printf(", %d malformed lines skipped", log.bad_lines);
      std::printf("\n");
      if (log.bad_lines > 0) std::printf("  first: %s\n", log.first_bad_line.c_str());
      *scans = std::move(log.scans);
    }
  } else {
    logs::BagReadOptions options;
    options.scan_topic = args.topic.empty() ? config.scan_topic : args.topic;
    options.odom_topic = args.odom_topic;
    options.base_frame = config.base_frame;
    options.odom_frame = config.odom_frame;
    options.sensor_pose = args.sensor_pose;
    options.read_odometry = config.use_odometry;
    options.skip_bad_messages = args.skip_bad_lines;
    logs::BagLog log;
    error = logs::ReadBag(args.bag, options, &log);
    if (error.empty()) {
      std::printf("%s: %zu of %d scans on %s; laser mounting: %s; odometry: %s\n",
                  args.bag.c_str(), log.scans.size(), log.scans_in_bag,
                  options.scan_topic.c_str(), log.mounting_source.c_str(),
                  log.odometry_source.c_str());
      if (log.dropped_no_transform > 0) {
        std::printf("  %d scans dropped without a mounting transform; first: %s\n",
                    log.dropped_no_transform, log.first_drop.c_str());
      }
      if (log.scans_without_odometry > 0) {
        std::printf("  %d scans without odometry at their stamp\n", log.scans_without_odometry);
      }
      if (log.bad_messages > 0) {
        std::printf("  %d malformed messages skipped; first: %s\n", log.bad_messages,
                    log.first_bad_message.c_str());
      }
      *scans = std::move(log.scans);
    }
  }
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return false;
  }
  if (args.min_scan_interval > 0.0) {
    const std::size_t read = scans->size();
    logs::KeepScansApart(args.min_scan_interval, scans);
    std::printf("kept %zu of %zu scans, at least %.3f s apart\n", scans->size(), read,
                args.min_scan_interval);
  }
  if (args.max_scans >= 0 && static_cast<long>(scans->size()) > args.max_scans) {
    scans->resize(args.max_scans);
  }
  return true;
}

// What the run did, scan by scan and in the background.
void PrintRun(const logs::OfflineConfig& config, const std::vector<logs::LogScan>& scans,
              const logs::OfflineRun& run) {
  const logs::SampleStatistics ms = logs::Summarize(run.scan_ms);
  int with_odometry = 0;
  for (const logs::LogScan& s : scans) with_odometry += s.odometry ? 1 : 0;
  const std::string odometry_use =
      !config.use_odometry ? "off" : with_odometry == 0 ? "none in the log" : "on";
  std::printf("lattice %s, cell %.4f m, odometry %s: %zu scans, %d matched (%d recovered), "
              "%d too few points, %d invalid, %d map updates; %d stamps lowered to keep time "
              "non-decreasing\n",
              config.slam.lattice.c_str(), config.slam.map_resolution,
              odometry_use.c_str(), scans.size(), run.count(ScanOutcome::kMatched),
              run.recoveries, run.count(ScanOutcome::kTooFewPoints),
              run.count(ScanOutcome::kInvalidScan), run.map_updates, run.stamps_lowered);
  if (!run.first_rejection.empty()) std::printf("  first unused: %s\n", run.first_rejection.c_str());
  const auto in_state = [&run](TrackingState state) {
    const auto it = run.tracking.find(state);
    return it == run.tracking.end() ? 0 : it->second;
  };
  std::printf("tracking: %d scans ok, %d degraded, %d lost; lost %d times, relocalized %d "
              "times, started over on a new submap %d times\n",
              in_state(TrackingState::kOk), in_state(TrackingState::kDegraded),
              in_state(TrackingState::kLost), run.times_lost, run.relocalizations, run.restarts);
  if (!run.first_lost.empty()) std::printf("  first lost: %s\n", run.first_lost.c_str());
  if (run.odometry_faults > 0) {
    std::printf("  warning: %d odometry faults (increments dropped); first: %s\n",
                run.odometry_faults, run.first_odometry_fault.c_str());
  }
  const logs::SampleStatistics cpu = logs::Summarize(run.scan_cpu_ms);
  std::printf("per scan %.3f ms mean, %.3f median, %.3f p99, %.3f max (on its core: %.3f mean, "
              "%.3f p99); log %.1f s in %.2f s (%.0fx real time)\n",
              ms.mean, ms.median, ms.p99, ms.max, cpu.mean, cpu.p99, run.log_seconds,
              run.processing_seconds + run.finish_seconds, run.RealtimeFactor());
  if (run.loop_closure) PrintLoopClosure(run);
}

// Runs the SLAM over `scans`, prints what the run did and writes its files. The SLAM's maps
// are released on return, before the caller's consistency check builds a grid of its own: on
// a large building the two together were the run's peak memory.
bool RunAndWrite(const Args& args, const logs::OfflineConfig& config,
                 const std::vector<logs::LogScan>& scans, logs::OfflineRun* result) {
  logs::OfflineOptions run_options;
  run_options.use_odometry = config.use_odometry;
  run_options.sensor_pose = args.sensor_pose;
  run_options.pace = args.pace;
  Slam slam(config.slam);
  if (!args.map.empty()) {
    // Placed before the map is loaded, so the map's next update is measured from there (as it is
    // when the node loads a map and is given an initialpose), and checked against it after.
    if (args.initial_pose) slam.SetPose(*args.initial_pose);
    std::string error = io::LoadSlamMap(args.map, &slam);
    if (error.empty() && args.initial_pose && !slam.SetPose(*args.initial_pose)) {
      error = "--initial-pose: " + slam.OutOfReach(*args.initial_pose);
    }
    if (!error.empty()) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return false;
    }
    std::printf("map %s loaded (%s); the robot starts at %.3f %.3f %.3f\n", args.map.c_str(),
                config.slam.update_map ? "mapping goes on" : "localization only",
                slam.pose().x, slam.pose().y, slam.pose().theta);
  }
  logs::ProgressBar bar(stderr, static_cast<long>(scans.size()), "hex_slam_offline",
                        logs::ProgressBar::ForStream(stderr));
  logs::ProgressCallback progress;
  if (args.progress) progress = [&bar](std::size_t done, double t) { bar.Update(done, t); };
  *result = logs::RunOffline(scans, run_options, &slam, progress);
  const logs::OfflineRun& run = *result;
  if (args.progress) bar.Finish(run.processing_seconds);

  PrintRun(config, scans, run);

  if (!args.out.empty()) {
    std::vector<Pose2> odometry;
    for (const logs::LogScan& s : scans) {
      if (s.odometry) odometry.push_back(*s.odometry);
    }
    if (odometry.size() != scans.size()) odometry.clear();  // a partial path would mislead
    std::vector<std::string> written;
    std::string error = logs::WriteRunOutputs(args.out, slam, run.trajectory, odometry,
                                              logs::RunOutputOptions(), &written);
    if (error.empty() && run.loop_closure) {
      const std::string front_end = args.out + "/front_end_trajectory.tum";
      error = io::WriteTumTrajectory(front_end, run.front_end_trajectory);
      if (error.empty()) written.push_back(front_end);
    }
    if (!error.empty()) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return false;
    }
    std::printf("wrote");
    for (const std::string& w : written) std::printf(" %s", w.c_str());
    std::printf("\n");
  }
  return true;
}

int Main(int argc, char** argv) {
  Args args;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_offline", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args] { return CheckArgs(args); })) {
    return *status;
  }
  logs::OfflineConfig config;
  if (!Configure(args, &config)) return cli::kUsageError;
  std::vector<logs::LogScan> scans;
  if (!ReadLog(args, config, &scans)) return 1;

  // As in the node, so that a paced run's scan path costs what the node's does.
  if (!RetainFreedMemory()) std::fprintf(stderr, "note: the allocator keeps its own limits\n");
  logs::OfflineRun run;
  if (!RunAndWrite(args, config, scans, &run)) return 1;
  const logs::SampleStatistics ms = logs::Summarize(run.scan_ms);
  const logs::SampleStatistics cpu = logs::Summarize(run.scan_cpu_ms);
  const logs::SampleStatistics latency = logs::Summarize(run.pose_latency_ms);

  // Self-consistency without ground truth: every scan re-inserted at its estimated pose.
  std::vector<Pose2> poses;
  for (const io::StampedPose& p : run.trajectory) poses.push_back(p.pose);
  const logs::MapConsistencyReport consistency =
      logs::EvaluateMapConsistency(scans, poses, config.slam);
  std::printf("map consistency: scans' endpoints on cells of occupancy %.3f mean, %.3f at the "
              "5th percentile (all scans re-inserted at their poses)\n",
              consistency.agreement.mean, consistency.low_quantile);

  const mapping::LoopClosureStats& lc = run.loop_closure_stats;
  std::printf("RESULT scans=%zu matched=%d recoveries=%d mean_ms=%.4f median_ms=%.4f p99_ms=%.4f "
              "realtime_factor=%.1f peak_rss_mb=%.1f map_agreement=%.4f map_agreement_p05=%.4f "
              "loop_closure=%d nodes=%d submaps=%d searches=%ld loop_constraints=%d "
              "consistent=%d slipped=%d background_s=%.3f background_cpu_s=%.3f finish_s=%.3f "
              "map_draw_s=%.3f cpu_mean_ms=%.4f cpu_p99_ms=%.4f pace=%g latency_mean_ms=%.4f "
              "latency_p99_ms=%.4f\n",
              scans.size(), run.count(ScanOutcome::kMatched), run.recoveries, ms.mean, ms.median,
              ms.p99, run.RealtimeFactor(), logs::PeakResidentMegabytes(),
              consistency.agreement.mean, consistency.low_quantile, run.loop_closure ? 1 : 0,
              lc.nodes, lc.submaps, lc.search.local_searches + lc.search.global_searches,
              lc.loop_constraints, lc.loop_constraints_consistent, lc.slipped_nodes,
              lc.busy_seconds, lc.cpu_seconds, run.finish_seconds, run.map_draw_seconds,
              cpu.mean, cpu.p99, args.pace, latency.mean, latency.p99);
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
