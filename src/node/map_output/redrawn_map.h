// With loop closure: the map thread's own global map, drawn from the nodes at their optimised
// poses (mapping::DrawGlobalMap) whenever a new pose-graph solution arrives, with the nodes
// inserted since added at the solution's correction. /map, dynamic_map, the hex_map marker and
// save_map come from it, so they show the map as the pose graph has it, not the live map that
// drew each scan at the pose the front end had for it then. Drawing runs on the map thread from
// copies of the node list and the solution (shared pointers to immutable data): the SLAM lock is
// held only to copy them.
#ifndef HEX_SLAM_NODE_MAP_OUTPUT_REDRAWN_MAP_H_
#define HEX_SLAM_NODE_MAP_OUTPUT_REDRAWN_MAP_H_

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/mapping/loop_closure/pose_graph_solution.h"
#include "hex_slam/mapping/trajectory_node.h"
#include "hex_slam/mapping/slam_options.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace node {

using NodeList = std::vector<std::shared_ptr<const mapping::TrajectoryNode>>;

class RedrawnMap {
 public:
  // A pyramid as the SLAM's own (lattice, spacing, levels, model, growth).
  explicit RedrawnMap(const SlamOptions& options);

  // Brings the map to `nodes` at `solution`: redrawn from scratch (*all) when the solution is
  // not the one drawn or the nodes are not a continuation of those drawn (a reset); otherwise
  // the new nodes inserted, and `changed` extended by their world box.
  void Update(const NodeList& nodes, const std::shared_ptr<const mapping::PoseGraphSolution>& solution,
              Eigen::AlignedBox2d* changed, bool* all);

  // Whether Update would change anything.
  bool UpToDate(std::size_t nodes, std::uint64_t solution_version) const {
    return solution_ && nodes == drawn_nodes_ && solution_version == solution_->version;
  }

  const MapPyramid<HexLattice>* hex() const { return hex_.get(); }
  const MapPyramid<SquareLattice>* square() const { return square_.get(); }
  const std::shared_ptr<const mapping::PoseGraphSolution>& solution() const { return solution_; }
  int redraws() const { return redraws_; }
  double last_redraw_ms() const { return last_redraw_ms_; }

 private:
  std::unique_ptr<MapPyramid<HexLattice>> hex_;
  std::unique_ptr<MapPyramid<SquareLattice>> square_;
  std::shared_ptr<const mapping::PoseGraphSolution> solution_;  // the one drawn
  std::shared_ptr<const mapping::TrajectoryNode> first_node_;   // to tell a reset
  std::size_t drawn_nodes_ = 0;
  int redraws_ = 0;
  double last_redraw_ms_ = 0.0;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_MAP_OUTPUT_REDRAWN_MAP_H_
