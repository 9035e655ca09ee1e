#include "hex_slam/mapping/loop_closure/loop_closure_options.h"

#include <cmath>
#include <string>

#include "hex_slam/common/thread_priority.h"

namespace hex_slam {
namespace mapping {
namespace {

// A match a metre from odometry's prediction is no agreement: the bound only catches typos.
constexpr double kMaxConfirmDistance = 1.0;  // m

}  // namespace

std::vector<std::string> SubmapOptions::Validate() const {
  std::vector<std::string> errors;
  if (num_scans < 1) errors.push_back("submap_num_scans must be >= 1");
  if (!(node_point_spacing_cells >= 0.0 && std::isfinite(node_point_spacing_cells))) {
    errors.push_back("submap_node_point_spacing_cells must be finite and >= 0");
  }
  return errors;
}

std::vector<std::string> LoopClosureOptions::Validate() const {
  std::vector<std::string> errors = submaps.Validate();
  for (const std::string& e : constraints.Validate()) errors.push_back(e);
  for (const std::string& e : pose_graph.Validate()) errors.push_back(e);
  if (optimize_every_n_nodes < 1) {
    errors.push_back("loop_closure_optimize_every_n_nodes must be >= 1");
  }
  if (!(odometry_confirms_distance >= 0.0 && odometry_confirms_distance <= kMaxConfirmDistance)) {
    errors.push_back("loop_closure_odometry_confirms_distance must lie in [0, 1] m");
  }
  if (!(odometry_confirms_angle >= 0.0 && odometry_confirms_angle <= M_PI)) {
    errors.push_back("loop_closure_odometry_confirms_angle must lie in [0, pi]");
  }
  if (restart_after_lost_scans < 0) {
    errors.push_back("loop_closure_restart_after_lost_scans must be >= 0");
  }
  if (max_queued_submaps < 0) errors.push_back("loop_closure_max_queued_submaps must be >= 0");
  if (max_queued_submap_pyramids < -1) {
    errors.push_back("loop_closure_max_queued_submap_pyramids must be >= -1");
  }
  if (worker_niceness < 0 || worker_niceness > kWeakestNiceness) {
    errors.push_back("loop_closure_worker_niceness must be in [0, " +
                     std::to_string(kWeakestNiceness) + "]");
  }
  return errors;
}

}  // namespace mapping
}  // namespace hex_slam
