// A node of the pose graph: one scan the front end inserted into its submaps, kept (immutable,
// shared between the scan path and the loop-closure worker) so the worker can match it against
// other submaps and the global map can be drawn again at its optimised pose.
#ifndef HEX_SLAM_MAPPING_TRAJECTORY_NODE_H_
#define HEX_SLAM_MAPPING_TRAJECTORY_NODE_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace mapping {

struct TrajectoryNode {
  int id = 0;
  double stamp = 0.0;  // s, of the scan
  Pose2 local_pose;    // the robot in the front end's frame when the scan was inserted
  Eigen::Vector2d sensor_origin = Eigen::Vector2d::Zero();  // the laser in the robot frame
  // The scan's valid endpoints in the robot frame, thinned so no two consecutive ones are closer
  // than a fraction of the finest cell (SubmapOptions::node_point_spacing_cells).
  std::vector<Eigen::Vector2d> points;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_TRAJECTORY_NODE_H_
