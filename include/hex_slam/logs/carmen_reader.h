// CARMEN log files (the format of the Freiburg and Intel benchmark logs): one message per line,
// "NAME fields... ipc_timestamp hostname logger_timestamp". Read here:
//   FLASER n r1..rn x y theta odom_x odom_y odom_theta            (front laser; 180° fan)
//   ROBOTLASER1 type start fov resolution max_range accuracy remission_mode n r1..rn
//               m v1..vm laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv f s t
//   RAWLASER1..4 type start fov resolution max_range accuracy remission_mode n r1..rn m v1..vm
//   ODOM x y theta tv rv accel
// Poses in laser lines are odometry: the base's (odom_*/robot_*) and the laser's; their
// difference is the laser's mounting. RAWLASER lines carry no pose: their odometry is
// interpolated from the ODOM lines around them. Other messages (PARAM, SYNC, TRUEPOS, ...) and
// '#' comments are skipped and counted. Stamps are the ipc ones, the benchmarks' time base,
// kept as written even where they go backwards (see stamp_order.h).
#ifndef HEX_SLAM_LOGS_CARMEN_READER_H_
#define HEX_SLAM_LOGS_CARMEN_READER_H_

#include <istream>
#include <string>
#include <vector>

#include "hex_slam/logs/log_scan.h"

namespace hex_slam {
namespace logs {

struct CarmenReadOptions {
  // The laser message to read ("FLASER", "ROBOTLASER1", "RAWLASER1", ...). Empty: the first
  // laser message in the file; lines of other lasers are then skipped (they sit elsewhere on the
  // robot and would be matched as if they were this one).
  std::string laser_message;
  // Readings at or beyond this (m) are "no return": SICK scanners log 81.83 for those. They
  // become +inf (REP 117). ROBOTLASER1 and RAWLASER lines give their own maximum range.
  double flaser_no_return_range = 80.0;
  // A malformed line is an error naming the line; with this set it is skipped and counted.
  bool skip_bad_lines = false;
};

struct CarmenLog {
  std::string laser_message;   // the laser message that was read
  std::vector<LogScan> scans;  // file order
  int odometry_lines = 0;
  int other_lines = 0;  // messages not read (other types, other lasers, comments)
  int bad_lines = 0;    // malformed lines skipped (skip_bad_lines only)
  std::string first_bad_line;  // the first of them, as an error message
};

// Returns an empty string or an error ("file:line: what is wrong").
std::string ReadCarmenLog(const std::string& path, const CarmenReadOptions& options,
                          CarmenLog* log);
// The same from a stream; `name` prefixes error messages.
std::string ParseCarmenLog(std::istream& in, const std::string& name,
                           const CarmenReadOptions& options, CarmenLog* log);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_CARMEN_READER_H_
