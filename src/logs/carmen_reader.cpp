#include "hex_slam/logs/carmen_reader.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/io/bounded_line.h"
#include "hex_slam/logs/evaluation/pose_interpolation.h"

namespace hex_slam {
namespace logs {
namespace {

// A reading count beyond this is a corrupt line, not a laser.
constexpr long kMaxReadings = kMaxScanReadings;
// The longest line read: kMaxReadings readings and as many remissions at up to ~12 characters
// each, with room to spare. A longer line (a file without newlines) is refused, not buffered.
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 22;
// The laser geometry a ROBOTLASER / RAWLASER line may state: angles within a turn, a maximum
// range no 2D lidar comes near.
constexpr double kMaxFanAngle = 2.0 * M_PI + 1e-6;
constexpr double kMaxLaserRange = 1e4;  // m
// After the last pose or remission of every message: ipc_timestamp [hostname [logger_timestamp]].
constexpr std::size_t kMaxTrailingFields = 3;
// FLASER lines state no geometry: CARMEN's front laser is a 180° fan starting at -90°.
constexpr double kFlaserStartAngle = -0.5 * M_PI;
constexpr double kFlaserFieldOfView = M_PI;
// Fields after the pose(s) of every message: ipc_timestamp hostname logger_timestamp. Only the
// ipc stamp is required; some converters drop the other two.
constexpr int kMinTrailingFields = 1;

// The whitespace-separated fields of one line, parsed on demand.
class Fields {
 public:
  explicit Fields(const std::string& line) {
    std::istringstream s(line);
    std::string word;
    while (s >> word) words_.push_back(word);
  }
  std::size_t size() const { return words_.size(); }
  const std::string& operator[](std::size_t i) const { return words_[i]; }
  // Any number, including nan and inf (ranges may be either).
  bool Number(std::size_t i, double* value) const {
    if (i >= words_.size()) return false;
    const char* begin = words_[i].c_str();
    char* end = nullptr;
    *value = std::strtod(begin, &end);
    return end != begin && *end == '\0';
  }
  bool Finite(std::size_t i, double* value) const { return Number(i, value) && std::isfinite(*value); }
  bool Count(std::size_t i, long* value) const {
    double v = 0.0;
    if (!Finite(i, &v) || v < 0.0 || v > kMaxReadings || v != std::floor(v)) return false;
    *value = static_cast<long>(v);
    return true;
  }
  bool PoseAt(std::size_t i, Pose2* pose) const {
    return Finite(i, &pose->x) && Finite(i + 1, &pose->y) && Finite(i + 2, &pose->theta);
  }
  // Whether fields [first, first + n) are all finite numbers; the first that is not, in `bad`.
  bool AllFinite(std::size_t first, std::size_t n, std::size_t* bad) const {
    double v = 0.0;
    for (std::size_t i = first; i < first + n; ++i) {
      if (!Finite(i, &v)) {
        *bad = i;
        return false;
      }
    }
    return true;
  }

 private:
  std::vector<std::string> words_;
};

// The laser in the base frame from both poses in the odometry frame. Computed from differences,
// so a laser logged at the base's pose (Intel) gets exactly the identity.
Pose2 Mounting(const Pose2& base, const Pose2& laser) {
  const double c = std::cos(base.theta), s = std::sin(base.theta);
  const double dx = laser.x - base.x, dy = laser.y - base.y;
  return Pose2(c * dx + s * dy, -s * dx + c * dy, NormalizeAngle(laser.theta - base.theta));
}

bool IsLaserMessage(const std::string& name) {
  return name == "FLASER" || name == "ROBOTLASER1" || name == "ROBOTLASER2" ||
         name == "RAWLASER1" || name == "RAWLASER2" || name == "RAWLASER3" || name == "RAWLASER4";
}

// Copies `count` readings from field `first` on, readings >= no_return becoming +inf. A reading
// may be NaN or inf (the sanitizer counts and drops those), never negative.
std::string ReadRanges(const Fields& f, std::size_t first, long count, double no_return,
                       std::vector<float>* ranges) {
  ranges->resize(count);
  for (long i = 0; i < count; ++i) {
    double r = 0.0;
    if (!f.Number(first + i, &r)) {
      return f[0] + " reading " + std::to_string(i + 1) + " '" +
             (first + i < f.size() ? f[first + i] : "") + "' is not a number";
    }
    if (r < 0.0) {
      return f[0] + " reading " + std::to_string(i + 1) + " (" + f[first + i] + ") is negative";
    }
    (*ranges)[i] = r >= no_return ? std::numeric_limits<float>::infinity() : static_cast<float>(r);
  }
  return "";
}

// Checks the fields after `at`: ipc_timestamp, then optionally hostname (not a number) and
// logger_timestamp, and nothing more. Extra fields mean the line holds more than it declares
// (more readings than its count): they would otherwise be read as poses and stamps.
std::string CheckTrailing(const Fields& f, std::size_t at, const std::string& counted) {
  const std::size_t trailing = f.size() - at;
  double v = 0.0;
  const bool host_is_number = trailing >= 2 && f.Number(at + 1, &v);
  if (trailing > kMaxTrailingFields || host_is_number) {
    return f[0] + " line has " + std::to_string(f.size()) + " fields, more than " + counted +
           " and 'ipc_timestamp hostname logger_timestamp' take: does the count match the " +
           "readings?";
  }
  if (trailing == 3 && !f.Finite(at + 2, &v)) {
    return f[0] + " logger_timestamp '" + f[at + 2] + "' is not a finite number";
  }
  return "";
}

// The checks every message's poses and stamp share.
std::string CheckPoseFields(const Fields& f, const Pose2& base, const Pose2* laser, double stamp) {
  std::string error = CheckPose(base, f[0] + (laser ? " robot pose" : " pose"));
  if (error.empty() && laser) error = CheckPose(*laser, f[0] + " laser pose");
  if (error.empty()) error = CheckStamp(stamp, f[0] + " ipc_timestamp");
  return error;
}

void SetFan(double start, double increment, double max_range, LaserScan* scan) {
  scan->angle_min = start;
  scan->angle_increment = increment;
  scan->angle_max = start + increment * (static_cast<double>(scan->ranges.size()) - 1.0);
  scan->range_min = 0.0;
  scan->range_max = max_range;
}

std::string ExpectFields(const Fields& f, std::size_t needed) {
  if (f.size() >= needed) return "";
  return f[0] + " line has " + std::to_string(f.size()) + " fields, needs at least " +
         std::to_string(needed);
}

// FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp ...
std::string ParseFlaser(const Fields& f, const CarmenReadOptions& options, LogScan* out) {
  long n = 0;
  if (!f.Count(1, &n) || n < 1) return "FLASER reading count '" + (f.size() > 1 ? f[1] : "") +
                                        "' is not a count in [1, " +
                                        std::to_string(kMaxReadings) + "]";
  const std::size_t pose_at = 2 + n;
  std::string error = ExpectFields(f, pose_at + 6 + kMinTrailingFields);
  if (error.empty()) {
    error = CheckTrailing(f, pose_at + 6, std::to_string(n) + " readings, two poses");
  }
  if (error.empty()) {
    error = ReadRanges(f, 2, n, options.flaser_no_return_range, &out->scan.ranges);
  }
  if (!error.empty()) return error;
  Pose2 laser, base;
  if (!f.PoseAt(pose_at, &laser) || !f.PoseAt(pose_at + 3, &base) ||
      !f.Finite(pose_at + 6, &out->scan.stamp)) {
    return "FLASER pose or timestamp is not a finite number";
  }
  error = CheckPoseFields(f, base, &laser, out->scan.stamp);
  if (error.empty()) error = CheckSensorPose(Mounting(base, laser), "FLASER laser mounting");
  if (!error.empty()) return error;
  // An odd count includes both ends of the fan (181 beams, 1°); an even one starts at -90°.
  const double increment = kFlaserFieldOfView / static_cast<double>(n % 2 == 1 && n > 1 ? n - 1 : n);
  SetFan(kFlaserStartAngle, increment, options.flaser_no_return_range, &out->scan);
  out->odometry = base;
  out->sensor_pose = Mounting(base, laser);
  return "";
}

// The common head of ROBOTLASER and RAWLASER: type start fov resolution max_range accuracy
// remission_mode n r1..rn m v1..vm. Returns the index of the field after the remissions.
std::string ParseLaserHead(const Fields& f, LogScan* out, std::size_t* next) {
  std::string error = ExpectFields(f, 9);
  if (!error.empty()) return error;
  double start = 0.0, fov = 0.0, resolution = 0.0, max_range = 0.0, accuracy = 0.0, mode = 0.0;
  if (!f.Finite(2, &start) || !f.Finite(3, &fov) || !f.Finite(4, &resolution) ||
      !f.Finite(5, &max_range) || !f.Finite(6, &accuracy) || !f.Finite(7, &mode)) {
    return f[0] + " start angle, field of view, resolution, maximum range, accuracy or " +
           "remission mode is not a finite number";
  }
  if (!(std::abs(start) <= kMaxFanAngle && std::abs(fov) <= kMaxFanAngle &&
        std::abs(resolution) <= kMaxFanAngle)) {
    return f[0] + " start angle, field of view or resolution is beyond a full turn (rad)";
  }
  if (resolution == 0.0 || !(max_range > 0.0 && max_range <= kMaxLaserRange)) {
    return f[0] + " needs a non-zero angular resolution and a maximum range in (0, " +
           std::to_string(static_cast<int>(kMaxLaserRange)) + "] m";
  }
  long n = 0;
  if (!f.Count(8, &n) || n < 1) return f[0] + " reading count is not a count in [1, " +
                                        std::to_string(kMaxReadings) + "]";
  error = ExpectFields(f, 9 + n + 1);
  if (error.empty()) error = ReadRanges(f, 9, n, max_range, &out->scan.ranges);
  if (!error.empty()) return error;
  long m = 0;
  if (!f.Count(9 + n, &m)) return f[0] + " remission count is not a count";
  error = ExpectFields(f, 9 + n + 1 + m);
  if (!error.empty()) return error;
  std::size_t bad = 0;
  if (!f.AllFinite(9 + n + 1, m, &bad)) {
    return f[0] + " remission " + std::to_string(bad - (9 + n)) + " is not a finite number";
  }
  SetFan(start, resolution, max_range, &out->scan);
  *next = 9 + n + 1 + m;
  return "";
}

std::string ParseRobotLaser(const Fields& f, LogScan* out) {
  std::size_t at = 0;
  std::string error = ParseLaserHead(f, out, &at);
  if (error.empty()) error = ExpectFields(f, at + 11 + kMinTrailingFields);
  if (error.empty()) {
    error = CheckTrailing(f, at + 11, "its readings, remissions, poses and velocities");
  }
  if (!error.empty()) return error;
  Pose2 laser, base;
  std::size_t bad = 0;
  if (!f.PoseAt(at, &laser) || !f.PoseAt(at + 3, &base) || !f.AllFinite(at + 6, 5, &bad) ||
      !f.Finite(at + 11, &out->scan.stamp)) {
    return f[0] + " pose, velocity or timestamp is not a finite number";
  }
  error = CheckPoseFields(f, base, &laser, out->scan.stamp);
  if (error.empty()) error = CheckSensorPose(Mounting(base, laser), f[0] + " laser mounting");
  if (!error.empty()) return error;
  out->odometry = base;
  out->sensor_pose = Mounting(base, laser);
  return "";
}

std::string ParseRawLaser(const Fields& f, LogScan* out) {
  std::size_t at = 0;
  std::string error = ParseLaserHead(f, out, &at);
  if (error.empty()) error = ExpectFields(f, at + kMinTrailingFields);
  if (error.empty()) error = CheckTrailing(f, at, "its readings and remissions");
  if (!error.empty()) return error;
  if (!f.Finite(at, &out->scan.stamp)) return f[0] + " timestamp is not a finite number";
  return CheckStamp(out->scan.stamp, f[0] + " ipc_timestamp");
}

struct OdometrySample {
  double stamp = 0.0;
  Pose2 pose;
};

// ODOM x y theta tv rv accel ipc_timestamp ...
std::string ParseOdometry(const Fields& f, OdometrySample* out) {
  std::string error = ExpectFields(f, 7 + kMinTrailingFields);
  if (error.empty()) error = CheckTrailing(f, 7, "a pose and velocities");
  if (!error.empty()) return error;
  std::size_t bad = 0;
  if (!f.PoseAt(1, &out->pose) || !f.AllFinite(4, 3, &bad) || !f.Finite(7, &out->stamp)) {
    return "ODOM pose, velocity or timestamp is not a finite number";
  }
  return CheckPoseFields(f, out->pose, nullptr, out->stamp);
}

// A RAWLASER scan's odometry: interpolated between the ODOM lines just before and after it in
// the file when their stamps bracket it, else the nearer of the two in the file.
void AttachOdometry(const std::vector<OdometrySample>& odometry, std::size_t odometry_before,
                    LogScan* scan) {
  const bool has_prev = odometry_before > 0;
  const bool has_next = odometry_before < odometry.size();
  const double t = scan->scan.stamp;
  if (has_prev && has_next) {
    const OdometrySample& a = odometry[odometry_before - 1];
    const OdometrySample& b = odometry[odometry_before];
    if (a.stamp <= t && t <= b.stamp && b.stamp > a.stamp) {
      scan->odometry = InterpolatePose(a.pose, b.pose, (t - a.stamp) / (b.stamp - a.stamp));
      return;
    }
  }
  if (has_prev) {
    scan->odometry = odometry[odometry_before - 1].pose;
  } else if (has_next) {
    scan->odometry = odometry[odometry_before].pose;
  }
}

}  // namespace

std::string ParseCarmenLog(std::istream& in, const std::string& name,
                           const CarmenReadOptions& options, CarmenLog* log) {
  *log = CarmenLog();
  log->laser_message = options.laser_message;
  std::vector<OdometrySample> odometry;
  // RAWLASER scans waiting for odometry: (scan index, ODOM lines read before it).
  std::vector<std::pair<std::size_t, std::size_t>> raw_scans;
  std::string line;
  long number = 0;
  for (;;) {
    const io::LineStatus status = io::ReadBoundedLine(in, kMaxLineBytes, &line);
    if (status == io::LineStatus::kEnd) break;
    ++number;
    // Never skipped: the rest of such a file is not a log either.
    if (status == io::LineStatus::kTooLong) {
      return io::LineTooLongMessage(name, number, kMaxLineBytes);
    }
    const Fields f(line);
    if (f.size() == 0) continue;
    const std::string& message = f[0];
    if (message[0] == '#') {
      ++log->other_lines;
      continue;
    }
    std::string error;
    if (message == "ODOM") {
      OdometrySample sample;
      error = ParseOdometry(f, &sample);
      if (error.empty()) {
        odometry.push_back(sample);
        ++log->odometry_lines;
      }
    } else if (IsLaserMessage(message) &&
               (log->laser_message.empty() || log->laser_message == message)) {
      LogScan scan;
      if (message == "FLASER") {
        error = ParseFlaser(f, options, &scan);
      } else if (message.rfind("ROBOTLASER", 0) == 0) {
        error = ParseRobotLaser(f, &scan);
      } else {
        error = ParseRawLaser(f, &scan);
        if (error.empty()) raw_scans.emplace_back(log->scans.size(), odometry.size());
      }
      if (error.empty()) {
        log->laser_message = message;
        log->scans.push_back(std::move(scan));
      }
    } else {
      ++log->other_lines;
    }
    if (!error.empty()) {
      const std::string where = name + ":" + std::to_string(number) + ": " + error;
      if (!options.skip_bad_lines) return where;
      if (log->bad_lines++ == 0) log->first_bad_line = where;
    }
  }
  if (in.bad()) return name + ": read error after line " + std::to_string(number);
  for (const auto& [index, before] : raw_scans) AttachOdometry(odometry, before, &log->scans[index]);
  if (log->scans.empty()) {
    return name + ": no laser scans (FLASER, ROBOTLASER1/2 or RAWLASER1-4 lines" +
           (options.laser_message.empty() ? std::string() : " of type " + options.laser_message) +
           ")";
  }
  return "";
}

std::string ReadCarmenLog(const std::string& path, const CarmenReadOptions& options,
                          CarmenLog* log) {
  std::ifstream in(path);
  if (!in) return "cannot read " + path;
  return ParseCarmenLog(in, path, options, log);
}

}  // namespace logs
}  // namespace hex_slam
