#include "hex_slam/io/trajectory_io.h"

#include <cmath>
#include <iomanip>

#include "hex_slam/io/atomic_file.h"
#include "hex_slam/io/number_rows.h"

namespace hex_slam {
namespace io {

std::string WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses) {
  return WriteFileAtomically(path, [&poses](std::ostream& out) {
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
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    poses->push_back({v[0], Pose2(v[1], v[2], yaw)});
  });
}

}  // namespace io
}  // namespace hex_slam
