#include "hex_slam/common/input_limits.h"

#include <cmath>
#include <sstream>

namespace hex_slam {
namespace {

std::string Beyond(const std::string& what, const char* field, double value, double limit,
                   const char* unit) {
  std::ostringstream s;
  s << what << ": " << field << " = " << value;
  if (std::isfinite(value)) {
    s << " is beyond ±" << limit << " " << unit;
  } else {
    s << " is not a finite number";
  }
  return s.str();
}

}  // namespace

bool IsFinite(const Pose2& pose) {
  return std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta);
}

std::string CheckPose(const Pose2& pose, const std::string& what) {
  // Written as !(|v| <= limit) so NaN fails too.
  if (!(std::abs(pose.x) <= kMaxAbsCoordinate)) {
    return Beyond(what, "x", pose.x, kMaxAbsCoordinate, "m");
  }
  if (!(std::abs(pose.y) <= kMaxAbsCoordinate)) {
    return Beyond(what, "y", pose.y, kMaxAbsCoordinate, "m");
  }
  if (!(std::abs(pose.theta) <= kMaxAbsAngle)) {
    return Beyond(what, "yaw", pose.theta, kMaxAbsAngle, "rad");
  }
  return "";
}

std::string CheckSensorPose(const Pose2& pose, const std::string& what) {
  if (!IsFinite(pose)) return CheckPose(pose, what);
  const double offset = std::hypot(pose.x, pose.y);
  if (offset > kMaxSensorOffset) {
    std::ostringstream s;
    s << what << ": the laser sits " << offset << " m from the base, more than "
      << kMaxSensorOffset << " m (a calibration error?)";
    return s.str();
  }
  return CheckPose(pose, what);  // the heading, which the offset does not bound
}

std::string CheckStamp(double stamp, const std::string& what) {
  if (stamp >= 0.0 && stamp < kMaxRosTime) return "";
  std::ostringstream s;
  s.precision(12);
  s << what << ": stamp " << stamp << " s is outside ROS time [0, " << kMaxRosTime << ") s";
  return s.str();
}

}  // namespace hex_slam
