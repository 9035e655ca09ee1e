// carmen_to_bag: a CARMEN log as a ROS 1 bag that hex_slam_node (or hector_mapping) can replay:
// LaserScan on /scan in frame "laser", tf odom -> base_link and /odom from the log's odometry,
// base_link -> laser on /tf_static. Stamps that go backwards are lowered to their successor's.
#include <cstdio>
#include <optional>
#include <string>

#include "hex_slam/logs/bag_writer.h"
#include "hex_slam/logs/carmen_reader.h"
#include "command_line.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

struct Args {
  std::string carmen;
  std::string out;
  logs::CarmenReadOptions read_options;
  long max_scans = -1;  // < 0: all
};

void Declare(CLI::App* app, Args* args) {
  app->description(
      "Writes a CARMEN log as a ROS 1 bag hex_slam_node (or hector_mapping) can replay: /scan "
      "(frame laser), /tf odom->base_link and /odom (nav_msgs/Odometry) from the log's odometry, "
      "/tf_static base_link->laser. Stamps that go backwards are lowered to their successor's.");
  app->footer("Ends with: RESULT scans=... odometry=... stamps_lowered=...");
  app->add_option("--carmen", args->carmen, "the CARMEN log")->check(cli::NonEmpty())->required();
  app->add_option("--out", args->out, "the bag to write")->check(cli::NonEmpty())->required();
  app->add_option("--laser", args->read_options.laser_message,
                  "the CARMEN laser message (default: the first one in the file)")
      ->check(cli::NonEmpty());
  app->add_option("--max-scans", args->max_scans, "keeps only the first N scans")
      ->check(cli::NonNegative());
}

int Main(int argc, char** argv) {
  Args args;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "carmen_to_bag", argc, argv, [&args](CLI::App* app) { Declare(app, &args); })) {
    return *status;
  }
  logs::CarmenLog log;
  std::string error = logs::ReadCarmenLog(args.carmen, args.read_options, &log);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  if (args.max_scans >= 0 && static_cast<long>(log.scans.size()) > args.max_scans) {
    log.scans.resize(args.max_scans);
  }
  logs::BagWriteReport report;
  error = logs::WriteLogAsBag(log.scans, args.out, logs::BagWriteOptions(), &report);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s -> %s: %d %s scans, %d with odometry, %d stamps lowered to keep time "
              "non-decreasing%s\n",
              args.carmen.c_str(), args.out.c_str(), report.scans, log.laser_message.c_str(),
              report.odometry, report.stamps_lowered,
              report.mounting_varies ? "; the laser mounting varies, the first one was written"
                                     : "");
  std::printf("RESULT scans=%d odometry=%d stamps_lowered=%d\n", report.scans, report.odometry,
              report.stamps_lowered);
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
