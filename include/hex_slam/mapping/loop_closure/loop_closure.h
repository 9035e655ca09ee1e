// The scan path's side of loop closure, for one lattice: the active submaps the front end matches
// against and inserts into, the nodes made from inserted scans, and the worker they are handed to.
// Owned and called by Slam on the scan thread (not thread-safe itself); the worker's results are
// read from the LatestSolution board, from any thread.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_H_

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/mapping/active_submaps.h"
#include "hex_slam/mapping/loop_closure/loop_closure_options.h"
#include "hex_slam/mapping/loop_closure/loop_closure_worker.h"
#include "hex_slam/mapping/loop_closure/pose_graph_solution.h"
#include "hex_slam/mapping/trajectory_node.h"
#include "hex_slam/matching/scan_matcher.h"

namespace hex_slam {
namespace mapping {

template <class Lattice>
class LoopClosure {
 public:
  LoopClosure(const LoopClosureOptions& options, const ScanMatcherOptions& refinement,
              const SubmapGridParameters& grid, std::shared_ptr<LatestSolution> board);

  // The pyramid the front end matches against (the older active submap's); null before the
  // first insertion.
  const MapPyramid<Lattice>* matching_maps() const {
    const Submap<Lattice>* s = active_.matching_submap();
    return s ? &s->maps() : nullptr;
  }

  // Completes the submap the next scan will be matched against, if the filler still holds scans
  // for it (after a submap switch): a live caller between scans does it here, not on the next
  // scan's latency. matching_maps() does the same when it is needed first.
  void CompleteMatchingSubmap() const { active_.matching_submap(); }

  // Inserts a scan taken at `local_pose` into the active submaps and queues it for the worker
  // as a node; `sensor_origin` and `points` are in the robot frame. Returns the node's id.
  int InsertScan(double stamp, const Pose2& local_pose, const Eigen::Vector2d& sensor_origin,
                 const std::vector<Eigen::Vector2d>& points);

  // The end of the trajectory: finishes the active submaps, then blocks until the worker has
  // searched and optimised everything. Scans inserted afterwards start new submaps.
  void FinishTrajectory();
  // Finishes the active submaps as they are, without waiting for the worker; the next inserted
  // scan starts a new submap. After a loss (Slam::StartOver) the motion between the nodes on
  // either side is odometry's, weighed as any other, and the worker's ordinary searches join the
  // stretches (searching the first new node at once over every whole submap, with the widest
  // local windows, added wrong constraints on the Freiburg hospital log: 5.6 m against 0.71 m).
  void FinishActiveSubmaps();

  const std::vector<std::shared_ptr<const TrajectoryNode>>& nodes() const { return nodes_; }
  LoopClosureStats stats() const { return worker_->stats(); }
  // The active submaps and the nodes' points (the worker's grid cache is in stats()).
  std::size_t MemoryBytes() const;

 private:
  SubmapOptions submap_options_;
  double node_point_spacing_;
  ActiveSubmaps<Lattice> active_;
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes_;
  std::vector<Eigen::Vector2d> local_points_;  // scratch
  std::unique_ptr<LoopClosureWorker<Lattice>> worker_;
};

// Redraws `maps` from scratch: every node's scan inserted at its pose in `solution` (or, for a
// node it does not know yet, at its front-end pose moved by the solution's correction).
template <class Lattice>
void DrawGlobalMap(const std::vector<std::shared_ptr<const TrajectoryNode>>& nodes,
                   const PoseGraphSolution& solution, MapPyramid<Lattice>* maps);
// Inserts nodes[first ..] into `maps` as DrawGlobalMap does (without clearing); `region`, if
// given, is extended by the world box of their rays.
template <class Lattice>
void DrawNodes(const std::vector<std::shared_ptr<const TrajectoryNode>>& nodes,
               std::size_t first, const PoseGraphSolution& solution, MapPyramid<Lattice>* maps,
               Eigen::AlignedBox2d* region = nullptr);

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_H_
