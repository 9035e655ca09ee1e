// hex_slam_loop_bench: loop closure on a simulated building (sim/building_loop.h: a 60 m × 32 m
// floor, twice round its 134 m corridor, a 5 Hz 361-beam lidar), against the truth. For each seed
// the same recorded drive runs with and without the log's drifting odometry, and with and without
// loop closure; prints the front end's drift and the optimised trajectory's error (position RMSE
// and worst pose after aligning the first pose, the RMSE after the rigid alignment that fits
// best: the shape alone, and the RMSE of the path as output, its map frame on the truth's start),
// the background work, and one RESULT line per run. --lidar-range and
// --lidar-noise make the sensor weaker, so the front end drifts more than with the SICK-like one.
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/logs/offline/offline_config.h"
#include "hex_slam/logs/offline/offline_runner.h"
#include "hex_slam/logs/offline/resource_usage.h"
#include "hex_slam/logs/offline/run_outputs.h"
#include "hex_slam/logs/evaluation/sample_statistics.h"
#include "hex_slam/logs/evaluation/trajectory_error.h"
#include "hex_slam/sim/building_loop.h"
#include "hex_slam/mapping/slam.h"
#include "command_line.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

// A lidar shorter than this sees no wall of the 2.4 m corridor from its middle.
constexpr double kMinLidarRange = 1.5;  // m
constexpr int kMaxCount = 1000;         // seeds or laps: beyond it a typo, not a run

// --odometry and --loop-closure: which of a setting's two runs to make.
const std::string kBoth = "both";
const std::string kOn = "on";
const std::string kOff = "off";

struct Args {
  int seeds = 3;
  int laps = 2;
  double odometry_noise_scale = 1.0;
  double lidar_range = 0.0;   // m; 0: the building's own lidar
  double lidar_noise = -1.0;  // m (range noise standard deviation); < 0: the building's own
  std::map<std::string, std::string> overrides;
  std::string out;  // optional: trajectories as TUM files
  std::vector<bool> odometry = {true, false};      // runs with and without the odometry
  std::vector<bool> loop_closure = {false, true};  // and with loop closure off and on
};

// "both" keeps `runs` (both settings, in their order); "on" or "off" makes only that run.
CLI::Option* AddRuns(CLI::App* app, const std::string& name, std::vector<bool>* runs,
                     const std::string& description) {
  return app
      ->add_option_function<std::string>(
          name,
          [runs](const std::string& choice) {
            if (choice != kBoth) *runs = {choice == kOn};
          },
          description)
      ->check(CLI::IsMember(std::vector<std::string>{kBoth, kOn, kOff}));
}

// The command line; --set's names are checked after parsing, against the SLAM's parameters
// (ConfigureSlam).
void Declare(CLI::App* app, Args* args) {
  app->description(
      "Drives the simulated building loop (a 60 m x 32 m floor, a 5 Hz 361-beam lidar) once per "
      "seed and runs the SLAM over the recording with and without its drifting odometry, and "
      "with and without loop closure, against the truth.");
  app->footer(
      "Each run ends with: RESULT seed=... odometry=... loop_closure=... front_rmse=... "
      "front_max=... front_aligned_rmse=... rmse=... max=... aligned_rmse=... as_output_rmse=... "
      "mean_ms=... p99_ms=... realtime_factor=... loop_constraints=... consistent=... "
      "background_s=... (front_*: the front end's path, the others the output's; position "
      "errors in m with the first pose on the truth's, aligned_rmse after the rigid alignment "
      "that fits best, as_output_rmse with the map frame on the truth's start)");
  app->add_option("--seeds", args->seeds, "drives with seeds 1 to N")
      ->check(CLI::Range(1, kMaxCount))
      ->capture_default_str();
  app->add_option("--laps", args->laps, "times round the corridor")
      ->check(CLI::Range(1, kMaxCount))
      ->capture_default_str();
  cli::AddNumber(app, "--odometry-noise-scale", &args->odometry_noise_scale,
                 "odometry drifts as OdometryNoise::Typical() times this (default 1)", 0.0);
  cli::AddSettings(app, "--set", &args->overrides, "changes a SLAM parameter for every run");
  AddRuns(app, "--odometry", &args->odometry, "runs with the odometry, without it, or both");
  AddRuns(app, "--loop-closure", &args->loop_closure,
          "runs with loop closure, without it, or both");
  app->add_option("--out", args->out,
                  "writes each run's map, pictures and trajectories (as hex_slam_offline, and "
                  "truth.tum) to DIR/seedN_...")
      ->check(cli::NonEmpty())
      ->type_name("DIR");
  cli::AddNumber(app, "--lidar-range", &args->lidar_range,
                 "the lidar's maximum range, m (default: the building's, 30 m); a shorter one "
                 "makes the front end drift more",
                 kMinLidarRange);
  cli::AddNumber(app, "--lidar-noise", &args->lidar_noise,
                 "the lidar's range noise standard deviation, m (default: the building's, "
                 "0.01 m)",
                 0.0);
}

// The SLAM's parameters for every run: hex_slam_offline's defaults, then --set. Returns what
// --set got wrong (an unknown name, a bad value), or nothing.
std::string ConfigureSlam(const Args& args, SlamOptions* options) {
  logs::UseOfflineDefaults(options);
  std::string error;
  for (const std::string& e : SlamParameterTable(options).Apply(args.overrides)) {
    error += (error.empty() ? "--set: " : "; ") + e;
  }
  return error;
}

struct Error {
  double rmse = 0.0;
  double max = 0.0;
  double aligned_rmse = 0.0;  // after the rigid alignment that fits best (the shape alone)
  // The path as the run output it: its map frame is where the first scan was taken (the run
  // starts the map there), so it is placed on the truth's first pose as it is. With loop closure
  // the optimisation moves the first pose too (the first submap is what it holds), which the
  // first-pose anchoring of `rmse` takes out.
  double as_output_rmse = 0.0;
};

std::vector<double> PositionErrors(const std::vector<io::StampedPose>& estimate,
                                   const std::vector<Pose2>& truth, const Pose2& align) {
  std::vector<double> errors;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    errors.push_back(((align * estimate[i].pose).translation() - truth[i].translation()).norm());
  }
  return errors;
}

// Position error after moving the estimate rigidly so its first pose is the truth's (the map
// frame is where the robot started), and after the alignment that fits best.
Error Compare(const std::vector<io::StampedPose>& estimate, const std::vector<Pose2>& truth) {
  std::vector<Eigen::Vector2d> from, to;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    from.push_back(estimate[i].pose.translation());
    to.push_back(truth[i].translation());
  }
  const logs::SampleStatistics first = logs::Summarize(
      PositionErrors(estimate, truth, truth.front() * estimate.front().pose.inverse()));
  const logs::SampleStatistics best =
      logs::Summarize(PositionErrors(estimate, truth, logs::AlignPoints(from, to)));
  const logs::SampleStatistics as_output =
      logs::Summarize(PositionErrors(estimate, truth, truth.front()));
  return {first.rmse, first.max, best.rmse, as_output.rmse};
}

sim::OdometryNoise ScaledNoise(double scale) {
  sim::OdometryNoise n = sim::OdometryNoise::Typical();
  n.translation_stddev *= scale;
  n.rotation_stddev *= scale;
  n.rotation_stddev_per_distance *= scale;
  n.translation_scale_error *= scale;
  n.rotation_scale_error *= scale;
  return n;
}

// The truth at each scan's stamp, for hex_slam_eval.
std::vector<io::StampedPose> Truth(const sim::RecordedDrive& drive) {
  std::vector<io::StampedPose> truth;
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    truth.push_back({drive.scans[i].stamp, drive.truth[i]});
  }
  return truth;
}

std::vector<logs::LogScan> AsLog(const sim::RecordedDrive& drive) {
  std::vector<logs::LogScan> log;
  for (std::size_t i = 0; i < drive.scans.size(); ++i) {
    log.push_back({drive.scans[i], Pose2(), drive.odometry[i]});
  }
  return log;
}

int Main(int argc, char** argv) {
  Args args;
  SlamOptions base;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_loop_bench", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args, &base] { return ConfigureSlam(args, &base); })) {
    return *status;
  }

  sim::BuildingLoop loop = sim::MakeBuildingLoop(args.laps);
  if (args.lidar_range > 0.0) loop.lidar.range_max = args.lidar_range;
  if (args.lidar_noise >= 0.0) loop.lidar.range_noise_stddev = args.lidar_noise;
  std::printf("building loop: %zu scans, %.0f s, %d laps; odometry noise x%.2f; lidar %.1f m, "
              "noise %.3f m\n",
              loop.truth.size(), loop.truth.size() * loop.scan_period, args.laps,
              args.odometry_noise_scale, loop.lidar.range_max, loop.lidar.range_noise_stddev);
  for (int seed = 1; seed <= args.seeds; ++seed) {
    const sim::RecordedDrive drive =
        sim::RecordBuildingLoop(loop, seed, ScaledNoise(args.odometry_noise_scale));
    const std::vector<logs::LogScan> log = AsLog(drive);
    std::vector<io::StampedPose> odometry;
    for (std::size_t i = 0; i < drive.odometry.size(); ++i) {
      odometry.push_back({i * loop.scan_period, drive.odometry[i]});
    }
    const Error odometry_error = Compare(odometry, drive.truth);
    std::printf("seed %d: odometry alone %.3f m RMSE, %.3f m worst\n", seed, odometry_error.rmse,
                odometry_error.max);
    for (const bool use_odometry : args.odometry) {
      for (const bool loop_closure : args.loop_closure) {
        SlamOptions options = base;
        options.loop_closure.enabled = loop_closure;
        Slam slam(options);
        logs::OfflineOptions run_options;
        run_options.use_odometry = use_odometry;
        const logs::OfflineRun run = logs::RunOffline(log, run_options, &slam);
        const Error front = Compare(run.front_end_trajectory, drive.truth);
        const Error optimised = Compare(run.trajectory, drive.truth);
        const logs::SampleStatistics ms = logs::Summarize(run.scan_ms);
        const mapping::LoopClosureStats& lc = run.loop_closure_stats;
        std::printf(
            "  %-7s %-15s front end %.3f m RMSE %.3f worst (%.3f aligned); %s %.3f m RMSE %.3f "
            "worst (%.3f aligned, %.3f as output); %.3f ms/scan (p99 %.3f); %.0fx real time\n",
            use_odometry ? "odom" : "no-odom", loop_closure ? "loop closure" : "no loop closure",
            front.rmse, front.max, front.aligned_rmse, loop_closure ? "optimised" : "(same)",
            optimised.rmse, optimised.max, optimised.aligned_rmse, optimised.as_output_rmse,
            ms.mean, ms.p99, run.RealtimeFactor());
        if (loop_closure) {
          std::printf("          %d nodes, %d submaps; %ld+%ld searches, %ld+%ld found, %d "
                      "consistent; background %.2f s (%.2f ms/node), %d optimisations %.2f s; "
                      "finish %.2f s\n",
                      lc.nodes, lc.submaps, lc.search.local_searches, lc.search.global_searches,
                      lc.search.local_found, lc.search.global_found, lc.loop_constraints_consistent,
                      lc.busy_seconds, lc.nodes ? 1e3 * lc.busy_seconds / lc.nodes : 0.0,
                      lc.optimizations, lc.optimization_seconds, run.finish_seconds);
          if (!lc.first_error.empty()) std::printf("          error: %s\n", lc.first_error.c_str());
        }
        std::printf("RESULT seed=%d odometry=%d loop_closure=%d front_rmse=%.4f front_max=%.4f "
                    "front_aligned_rmse=%.4f rmse=%.4f max=%.4f aligned_rmse=%.4f "
                    "as_output_rmse=%.4f mean_ms=%.4f "
                    "p99_ms=%.4f realtime_factor=%.1f loop_constraints=%d consistent=%d "
                    "background_s=%.3f\n",
                    seed, use_odometry, loop_closure, front.rmse, front.max, front.aligned_rmse,
                    optimised.rmse, optimised.max, optimised.aligned_rmse,
                    optimised.as_output_rmse, ms.mean, ms.p99, run.RealtimeFactor(),
                    lc.loop_constraints, lc.loop_constraints_consistent,
                    lc.busy_seconds);
        if (!args.out.empty()) {
          // The map and trajectory pictures and files of hex_slam_offline, one folder per run,
          // the front end's trajectory beside the optimised one.
          const std::string dir = args.out + "/seed" + std::to_string(seed) +
                                  (use_odometry ? "_odom" : "_noodom") +
                                  (loop_closure ? "_lc" : "_nolc");
          std::vector<std::string> written;
          std::string error = logs::WriteRunOutputs(dir, slam, run.trajectory, {},
                                                    logs::RunOutputOptions(), &written);
          if (error.empty() && loop_closure) {
            error = io::WriteTumTrajectory(dir + "/front_end_trajectory.tum",
                                           run.front_end_trajectory);
          }
          if (error.empty()) error = io::WriteTumTrajectory(dir + "/truth.tum", Truth(drive));
          if (!error.empty()) {
            std::fprintf(stderr, "error: %s\n", error.c_str());
            return 1;
          }
        }
      }
    }
  }
  std::printf("peak RSS %.0f MB\n", logs::PeakResidentMegabytes());
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
