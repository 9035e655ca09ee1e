// carmen_to_bag: a CARMEN log as a ROS 1 bag that hex_slam_node (or hector_mapping) can replay:
// LaserScan on /scan in frame "laser", tf odom -> base_link and /odom from the log's odometry,
// base_link -> laser on /tf_static. Stamps that go backwards are lowered to their successor's.
#include <cstdio>
#include <string>

#include "hex_slam/logs/bag_writer.h"
#include "hex_slam/logs/carmen_reader.h"
#include "hex_slam/logs/offline/tool_arguments.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

void Usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s --carmen FILE --out BAG [--laser NAME] [--max-scans N]\n"
               "  Writes /scan (frame laser), /tf odom->base_link, /tf_static base_link->laser\n"
               "  and /odom (nav_msgs/Odometry). --laser picks the CARMEN laser message (default:\n"
               "  the first one in the file); --max-scans keeps only the first N scans.\n",
               argv0);
}

int Main(int argc, char** argv) {
  std::string carmen, out;
  logs::CarmenReadOptions read_options;
  long max_scans = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (i + 1 >= argc) {
      Usage(argv[0]);
      return 2;
    }
    const std::string value = argv[++i];
    if (key == "--carmen") {
      carmen = value;
    } else if (key == "--out") {
      out = value;
    } else if (key == "--laser") {
      read_options.laser_message = value;
    } else if (key == "--max-scans") {
      if (!logs::ParseCount(value, &max_scans)) {
        std::fprintf(stderr, "error: --max-scans takes a count, got '%s'\n", value.c_str());
        return 2;
      }
    } else {
      std::fprintf(stderr, "error: unknown option %s\n", key.c_str());
      Usage(argv[0]);
      return 2;
    }
  }
  if (carmen.empty() || out.empty()) {
    Usage(argv[0]);
    return 2;
  }
  logs::CarmenLog log;
  std::string error = logs::ReadCarmenLog(carmen, read_options, &log);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  if (max_scans >= 0 && static_cast<long>(log.scans.size()) > max_scans) log.scans.resize(max_scans);
  logs::BagWriteReport report;
  error = logs::WriteLogAsBag(log.scans, out, logs::BagWriteOptions(), &report);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s -> %s: %d %s scans, %d with odometry, %d stamps lowered to keep time "
              "non-decreasing%s\n",
              carmen.c_str(), out.c_str(), report.scans, log.laser_message.c_str(),
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
