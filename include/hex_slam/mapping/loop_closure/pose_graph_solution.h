// What the loop-closure worker publishes after each optimisation, and the thread-safe board it is
// published on. Readers (the node's publishing thread, the offline tool) take the latest
// solution without ever waiting for the worker's work: the board's lock only guards a pointer.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_POSE_GRAPH_SOLUTION_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_POSE_GRAPH_SOLUTION_H_

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "hex_slam/mapping/loop_closure/pose_graph.h"
#include "hex_slam/mapping/trajectory_node.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace mapping {

struct PoseGraphSolution {
  // Counts the optimisations published on the board (and resets); 0 before the first.
  std::uint64_t version = 0;
  // The global (map) frame from the front end's (local) frame at the newest optimised node: a
  // front-end pose P is P' = correction·P in the map. The node republishes map → odom from it.
  Pose2 correction;
  // Global poses by id, of the nodes and submaps the optimisation knew.
  std::vector<Pose2> node_poses;
  std::vector<Pose2> submap_poses;
  // The nodes themselves (by id, as many as node_poses), to redraw the map from.
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  // Each submap's frame in the front end's frame (by id), and every constraint of the graph
  // (local ones say which nodes each submap holds); consecutive-node constraints follow from
  // the nodes' front-end poses. What a map file keeps of the graph.
  std::vector<Pose2> submap_local_poses;
  std::vector<Constraint> constraints;
  int local_constraints = 0;
  int loop_constraints = 0;

  // The pose in the map of a front-end pose `local` taken after node `node_id` (-1: before any
  // node, or a node this solution does not know yet: then `correction` is used).
  Pose2 ToGlobal(const Pose2& local, int node_id) const;
};

class LatestSolution {
 public:
  LatestSolution();

  std::shared_ptr<const PoseGraphSolution> Get() const;
  std::uint64_t version() const { return version_.load(); }
  // Replaces the solution (its version is set to the next one) and calls the listener.
  void Publish(PoseGraphSolution solution);
  // Called on the publishing (worker) thread after every Publish with the new version; keep it
  // short (e.g. wake the thread that republishes). Pass an empty function to remove it.
  void SetListener(std::function<void(std::uint64_t)> listener);

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const PoseGraphSolution> solution_;
  std::function<void(std::uint64_t)> listener_;
  std::atomic<std::uint64_t> version_{0};
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_POSE_GRAPH_SOLUTION_H_
