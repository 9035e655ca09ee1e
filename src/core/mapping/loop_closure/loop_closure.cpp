#include "hex_slam/mapping/loop_closure/loop_closure.h"

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {

template <class Lattice>
LoopClosure<Lattice>::LoopClosure(const LoopClosureOptions& options,
                                  const ScanMatcherOptions& refinement,
                                  const SubmapGridParameters& grid,
                                  std::shared_ptr<LatestSolution> board)
    : submap_options_(options.submaps),
      node_point_spacing_(options.submaps.node_point_spacing_cells * grid.finest_spacing),
      active_(options.submaps, grid),
      worker_(std::make_unique<LoopClosureWorker<Lattice>>(options, refinement, grid,
                                                           std::move(board))) {}

template <class Lattice>
int LoopClosure<Lattice>::InsertScan(double stamp, const Pose2& local_pose,
                                     const Eigen::Vector2d& sensor_origin,
                                     const std::vector<Eigen::Vector2d>& points) {
  local_points_.clear();
  const PointTransform to_local(local_pose);
  for (const Eigen::Vector2d& p : points) local_points_.push_back(to_local(p));
  std::vector<std::pair<int, Pose2>> inserted_into;
  std::shared_ptr<Submap<Lattice>> finished =
      active_.Insert(local_pose, local_pose * sensor_origin, local_points_, &inserted_into);

  auto node = std::make_shared<TrajectoryNode>();
  node->id = static_cast<int>(nodes_.size());
  node->stamp = stamp;
  node->local_pose = local_pose;
  node->sensor_origin = sensor_origin;
  DecimateScan(points, node_point_spacing_, &node->points);
  nodes_.push_back(node);
  worker_->AddNode(node, std::move(inserted_into));
  if (finished) worker_->AddFinishedSubmap(std::move(finished));
  return node->id;
}

template <class Lattice>
void LoopClosure<Lattice>::FinishTrajectory() {
  FinishActiveSubmaps();
  worker_->Flush();
}

template <class Lattice>
void LoopClosure<Lattice>::FinishActiveSubmaps() {
  for (auto& finished : active_.FinishAll()) worker_->AddFinishedSubmap(std::move(finished));
}

template <class Lattice>
std::size_t LoopClosure<Lattice>::MemoryBytes() const {
  std::size_t bytes = active_.MemoryBytes();
  for (const auto& n : nodes_) bytes += sizeof(TrajectoryNode) + n->points.size() * sizeof(Eigen::Vector2d);
  return bytes;
}

template <class Lattice>
void DrawGlobalMap(const std::vector<std::shared_ptr<const TrajectoryNode>>& nodes,
                   const PoseGraphSolution& solution, MapPyramid<Lattice>* maps) {
  maps->Clear();
  DrawNodes(nodes, 0, solution, maps);
}

template <class Lattice>
void DrawNodes(const std::vector<std::shared_ptr<const TrajectoryNode>>& nodes,
               std::size_t first, const PoseGraphSolution& solution, MapPyramid<Lattice>* maps,
               Eigen::AlignedBox2d* region) {
  if (first >= nodes.size()) return;
  // Every scan placed first, so the storage grows once for all of them: grown scan by scan, a
  // long-range log's map is copied into larger storage several times, each copy faulting its
  // pages in afresh.
  std::vector<Eigen::Vector2d> origins, points;
  std::vector<std::size_t> ends;  // points[ends[k-1], ends[k]) are the k-th node's
  Eigen::AlignedBox2d box;
  for (std::size_t i = first; i < nodes.size(); ++i) {
    const TrajectoryNode& node = *nodes[i];
    const Pose2 pose = solution.ToGlobal(node.local_pose, node.id);
    origins.push_back(pose * node.sensor_origin);
    box.extend(origins.back());
    const PointTransform to_global(pose);
    for (const Eigen::Vector2d& p : node.points) {
      points.push_back(to_global(p));
      box.extend(points.back());
    }
    ends.push_back(points.size());
  }
  if (!box.isEmpty()) maps->EnsureCovers(box);
  std::vector<Eigen::Vector2d> scan;
  for (std::size_t k = 0; k < origins.size(); ++k) {
    scan.assign(points.begin() + (k == 0 ? 0 : ends[k - 1]), points.begin() + ends[k]);
    maps->InsertScan(origins[k], scan);
  }
  if (region != nullptr) region->extend(box);
}

template class LoopClosure<HexLattice>;
template class LoopClosure<SquareLattice>;
template void DrawGlobalMap(const std::vector<std::shared_ptr<const TrajectoryNode>>&,
                            const PoseGraphSolution&, MapPyramid<HexLattice>*);
template void DrawGlobalMap(const std::vector<std::shared_ptr<const TrajectoryNode>>&,
                            const PoseGraphSolution&, MapPyramid<SquareLattice>*);
template void DrawNodes(const std::vector<std::shared_ptr<const TrajectoryNode>>&, std::size_t,
                        const PoseGraphSolution&, MapPyramid<HexLattice>*, Eigen::AlignedBox2d*);
template void DrawNodes(const std::vector<std::shared_ptr<const TrajectoryNode>>&, std::size_t,
                        const PoseGraphSolution&, MapPyramid<SquareLattice>*,
                        Eigen::AlignedBox2d*);

}  // namespace mapping
}  // namespace hex_slam
