// sim_to_bag: a simulated drive as a ROS 1 bag, for playing into the node as a real lidar would
// (the live benchmark's fast stream: scripts/live_bench). One of the paper's worlds (maze, rooms)
// driven along its path at the given scan rate, with the scenario's lidar (1 cm range noise) and
// drifting wheel odometry: /scan, /tf odom->base_link, /tf_static base_link->laser, /odom.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "hex_slam/logs/bag_writer.h"
#include "hex_slam/logs/offline/tool_arguments.h"
#include "hex_slam/sim/scenario.h"
#include "hex_slam/sim/scenario_run.h"
#include "tool_main.h"

#ifndef HEX_SLAM_SOURCE_DIR
#define HEX_SLAM_SOURCE_DIR "."
#endif

namespace hex_slam {
namespace {

// The drive's time 0 in the bag: ROS reads a zero stamp as "no time".
constexpr double kFirstStamp = 1000.0;  // s

struct Args {
  sim::ScenarioSpec spec;
  sim::ScenarioConditions conditions;
  long seed = 1;
  double duration = 0.0;  // s of the drive to keep; 0: all
  std::string out;
};

void Usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s --out BAG [--world maze|rooms] [--rate HZ] [--beams N]\n"
               "          [--range-max M] [--seed N] [--duration S]\n"
               "  Drives the world's path (worlds/) with a simulated lidar (default: the maze,\n"
               "  10 Hz, 1000 beams over 360 deg, 8 m) and writes it as a bag hex_slam_node and\n"
               "  hector_mapping can replay: /scan (frame laser), /tf odom->base_link, /tf_static\n"
               "  base_link->laser, /odom.\n",
               argv0);
}

// Returns false on a usage error, with a message in `error`.
bool Parse(int argc, char** argv, Args* args, std::string* error) {
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (i + 1 >= argc) {
      *error = key + " needs a value";
      return false;
    }
    const std::string value = argv[++i];
    long count = 0;
    double number = 0.0;
    if (key == "--out") {
      args->out = value;
    } else if (key == "--world") {
      args->spec.map = value;
    } else if (key == "--rate" && logs::ParseNumber(value, &number) && number > 0.0) {
      args->conditions.scan_rate = number;
    } else if (key == "--beams" && logs::ParseCount(value, &count) && count >= 3) {
      args->spec.beams = static_cast<int>(count);
    } else if (key == "--range-max" && logs::ParseNumber(value, &number) && number > 0.0) {
      args->conditions.range_max = number;
    } else if (key == "--duration" && logs::ParseNumber(value, &number) && number > 0.0) {
      args->duration = number;
    } else if (key == "--seed" && logs::ParseCount(value, &count)) {
      args->seed = count;
    } else {
      *error = "bad option or value: " + key + " " + value;
      return false;
    }
  }
  if (args->out.empty()) *error = "--out is required";
  return error->empty();
}

int Main(int argc, char** argv) {
  Args args;
  std::string error;
  if (!Parse(argc, argv, &args, &error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    Usage(argv[0]);
    return 2;
  }
  sim::Scenario scenario;
  error = sim::MakeScenario(args.spec,
                            sim::ScenarioFiles{std::string(HEX_SLAM_SOURCE_DIR) + "/worlds", ""},
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
