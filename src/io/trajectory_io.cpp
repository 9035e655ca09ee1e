#include "hex_slam/io/trajectory_io.h"

#include <cmath>
#include <iomanip>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/io/atomic_file.h"
#include "hex_slam/io/number_rows.h"

namespace hex_slam {
namespace io {
namespace {

// A written quaternion's squared norm may differ from 1 by rounding (9 digits here), not more;
// the tolerance is tf2's.
constexpr double kQuaternionTolerance = 0.01;

}  // namespace

std::string WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  AtomicFileSet file;
  AddTumTrajectory(path, poses, &file);
  return file.Commit();
}

void AddTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses,
                      AtomicFileSet* files) {
  files->Add(path, [&poses](std::ostream& out) {
    out << "# timestamp x y z qx qy qz qw\n" << std::fixed;
    for (const StampedPose& p : poses) {
      out << std::setprecision(6) << p.stamp << ' ' << std::setprecision(6) << p.pose.x << ' '
          << p.pose.y << " 0 0 0 " << std::setprecision(9) << std::sin(0.5 * p.pose.theta)
          << ' ' << std::cos(0.5 * p.pose.theta) << '\n';
    }
  });
}

std::string ReadTumTrajectory(const std::string& path, std::vector<StampedPose>* poses) {
  poses->clear();
  return ReadNumberRows(path, 8, "t x y z qx qy qz qw", [poses](const double* v) {
    // Yaw of a unit quaternion (ZYX convention).
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    const double norm2 = qx * qx + qy * qy + qz * qz + qw * qw;
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    const Pose2 pose(v[1], v[2], yaw);
    std::string error = CheckStamp(v[0], "t");
    if (error.empty()) error = CheckPose(pose, "pose");
    if (error.empty() && !(std::abs(norm2 - 1.0) <= kQuaternionTolerance)) {
      error = "(qx qy qz qw) is not a unit quaternion";
    }
    if (error.empty() && !(std::abs(v[3]) <= kMaxAbsCoordinate)) error = "z is out of bounds";
    if (error.empty()) poses->push_back({v[0], pose});
    return error;
  });
}

}  // namespace io
}  // namespace hex_slam
