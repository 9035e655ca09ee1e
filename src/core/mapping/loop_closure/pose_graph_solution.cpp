#include "hex_slam/mapping/loop_closure/pose_graph_solution.h"

#include <utility>

namespace hex_slam {
namespace mapping {

Pose2 PoseGraphSolution::ToGlobal(const Pose2& local, int node_id) const {
  if (node_id < 0 || node_id >= static_cast<int>(node_poses.size())) return correction * local;
  const TrajectoryNode& node = *nodes[node_id];
  return node_poses[node_id] * RelativePose(node.local_pose, local);
}

LatestSolution::LatestSolution() : solution_(std::make_shared<PoseGraphSolution>()) {}

std::shared_ptr<const PoseGraphSolution> LatestSolution::Get() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return solution_;
}

void LatestSolution::Publish(PoseGraphSolution solution) {
  std::function<void(std::uint64_t)> listener;
  std::uint64_t version = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    version = solution_->version + 1;
    solution.version = version;
    solution_ = std::make_shared<const PoseGraphSolution>(std::move(solution));
    version_.store(version);
    listener = listener_;
  }
  if (listener) listener(version);
}

void LatestSolution::SetListener(std::function<void(std::uint64_t)> listener) {
  std::lock_guard<std::mutex> lock(mutex_);
  listener_ = std::move(listener);
}

}  // namespace mapping
}  // namespace hex_slam
