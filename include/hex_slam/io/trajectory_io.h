// Trajectories in the TUM format: one "t x y z qx qy qz qw" line per pose, '#' comments. The 2D
// pose is embedded with z = 0 and a yaw-only quaternion.
#ifndef HEX_SLAM_IO_TRAJECTORY_IO_H_
#define HEX_SLAM_IO_TRAJECTORY_IO_H_

#include <string>
#include <vector>

#include "hex_slam/io/atomic_file.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace io {

struct StampedPose {
  double stamp = 0.0;  // s
  Pose2 pose;
};

// Written atomically. Returns an empty string or an error.
std::string WriteTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses);
// The same as one file of a set written together (atomic_file.h).
void AddTumTrajectory(const std::string& path, const std::vector<StampedPose>& poses,
                      AtomicFileSet* files);

// Reads a TUM file; the yaw is recovered from the quaternion (roll and pitch are ignored).
// Returns an empty string or an error naming the bad line.
std::string ReadTumTrajectory(const std::string& path, std::vector<StampedPose>* poses);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_TRAJECTORY_IO_H_
