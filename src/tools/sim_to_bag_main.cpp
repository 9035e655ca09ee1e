// sim_to_bag: a simulated drive as a ROS 1 bag, for playing into the node as a real lidar would
// (the live benchmark's fast stream: scripts/live_bench). One of the paper's worlds (maze, rooms)
// driven along its path at the given scan rate, with the scenario's lidar (1 cm range noise) and
// drifting wheel odometry: /scan, /tf odom->base_link, /tf_static base_link->laser, /odom.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/logs/bag_writer.h"
#include "hex_slam/sim/scenario.h"
#include "hex_slam/sim/scenario_run.h"
#include "command_line.h"
#include "tool_main.h"

#ifndef HEX_SLAM_SOURCE_DIR
#define HEX_SLAM_SOURCE_DIR "."
#endif

namespace hex_slam {
namespace {

// The drive's time 0 in the bag: ROS reads a zero stamp as "no time".
constexpr double kFirstStamp = 1000.0;  // s
// MakeScenario refuses fewer beams; the bag readers, a scan of more readings.
constexpr int kMinBeams = 3;
constexpr int kMaxBeams = static_cast<int>(kMaxScanReadings);

struct Args {
  sim::ScenarioSpec spec;
  sim::ScenarioConditions conditions;
  long seed = 1;
  double duration = 0.0;  // s of the drive to keep; 0: all
  std::string out;
};

void Declare(CLI::App* app, Args* args) {
  app->description(
      "Drives a world's path (worlds/) with a simulated lidar (1 cm range noise) and drifting "
      "wheel odometry, and writes it as a bag hex_slam_node and hector_mapping can replay: "
      "/scan (frame laser), /tf odom->base_link, /tf_static base_link->laser, /odom.");
  app->add_option("--out", args->out, "the bag to write")->check(cli::NonEmpty())->required();
  app->add_option("--world", args->spec.map, "maze or rooms")
      ->check(cli::NonEmpty())
      ->capture_default_str();
  cli::AddPositiveNumber(app, "--rate", &args->conditions.scan_rate, "scans per second, Hz")
      ->default_str(cli::ShownNumber(args->conditions.scan_rate));
  app->add_option("--beams", args->spec.beams, "readings per scan, over 360 deg")
      ->check(CLI::Range(kMinBeams, kMaxBeams))
      ->capture_default_str();
  cli::AddPositiveNumber(app, "--range-max", &args->conditions.range_max, "the lidar's range, m")
      ->default_str(cli::ShownNumber(args->conditions.range_max));
  app->add_option("--seed", args->seed, "the noise's seed")
      ->check(cli::NonNegative())
      ->capture_default_str();
  cli::AddPositiveNumber(app, "--duration", &args->duration,
                         "keeps only this many seconds of the drive (default: all of it)");
}

int Main(int argc, char** argv) {
  Args args;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "sim_to_bag", argc, argv, [&args](CLI::App* app) { Declare(app, &args); })) {
    return *status;
  }
  sim::Scenario scenario;
  std::string error = sim::MakeScenario(
      args.spec, sim::ScenarioFiles{std::string(HEX_SLAM_SOURCE_DIR) + "/worlds", ""},
      args.conditions, &scenario);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  const sim::RecordedDrive drive = sim::RecordDrive(scenario, static_cast<std::uint64_t>(args.seed));
  std::size_t count = drive.scans.size();
  if (args.duration > 0.0) {
    count = std::min(count, static_cast<std::size_t>(args.duration * args.conditions.scan_rate));
  }
  std::vector<logs::LogScan> scans(count);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    scans[i].scan = drive.scans[i];
    scans[i].scan.stamp += kFirstStamp;
    scans[i].odometry = drive.odometry[i];
  }
  logs::BagWriteReport report;
  error = logs::WriteLogAsBag(scans, args.out, logs::BagWriteOptions(), &report);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  std::printf("wrote %s: %d scans at %.1f Hz (%.1f s), %d beams, %s\n", args.out.c_str(),
              report.scans, args.conditions.scan_rate,
              report.scans / args.conditions.scan_rate, args.spec.beams, args.spec.Name().c_str());
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
