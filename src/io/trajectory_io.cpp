#include "hex_slam/io/trajectory_io.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "hex_slam/io/atomic_file.h"

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
  std::ifstream in(path);
  if (!in) return "cannot read " + path;
  poses->clear();
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double t, x, y, z, qx, qy, qz, qw;
    if (!(fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw) ||
        !std::isfinite(t + x + y + z + qx + qy + qz + qw)) {
      return path + ":" + std::to_string(number) + ": expected 8 numbers";
    }
    // Yaw of a unit quaternion (ZYX convention).
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz));
    poses->push_back({t, Pose2(x, y, yaw)});
  }
  return "";
}

}  // namespace io
}  // namespace hex_slam
