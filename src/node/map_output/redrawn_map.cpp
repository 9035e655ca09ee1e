#include "map_output/redrawn_map.h"

#include <chrono>

#include "hex_slam/mapping/loop_closure/loop_closure.h"

namespace hex_slam {
namespace node {
namespace {

template <class Lattice>
std::unique_ptr<MapPyramid<Lattice>> NewPyramid(const SlamOptions& o) {
  return std::make_unique<MapPyramid<Lattice>>(o.map_resolution, EffectiveLevels(o),
                                               MapOccupancyModel(o), MapGrowthPolicy(o),
                                               InitialMapExtent(o));
}

template <class Lattice>
void Draw(const NodeList& nodes, bool from_scratch, std::size_t first,
          const mapping::PoseGraphSolution& solution, MapPyramid<Lattice>* maps,
          Eigen::AlignedBox2d* changed) {
  if (maps == nullptr) return;
  // Continuing a drawing (even one that held no node yet) reports what it added in `changed`.
  if (from_scratch) {
    mapping::DrawGlobalMap(nodes, solution, maps);
  } else {
    mapping::DrawNodes(nodes, first, solution, maps, changed);
  }
}

}  // namespace

RedrawnMap::RedrawnMap(const SlamOptions& options) {
  if (options.lattice == "hex") {
    hex_ = NewPyramid<HexLattice>(options);
  } else {
    square_ = NewPyramid<SquareLattice>(options);
  }
}

void RedrawnMap::Update(const NodeList& nodes,
                        const std::shared_ptr<const mapping::PoseGraphSolution>& solution,
                        Eigen::AlignedBox2d* changed, bool* all) {
  *all = false;
  if (!solution) return;
  const bool continues = solution == solution_ && nodes.size() >= drawn_nodes_ &&
                         (drawn_nodes_ == 0 || nodes.front() == first_node_);
  *all = !continues;
  const std::size_t first = continues ? drawn_nodes_ : 0;
  if (first == nodes.size() && continues) return;
  const auto start = std::chrono::steady_clock::now();
  Draw(nodes, !continues, first, *solution, hex_.get(), changed);
  Draw(nodes, !continues, first, *solution, square_.get(), changed);
  if (!continues) {
    ++redraws_;
    last_redraw_ms_ = std::chrono::duration<double, std::milli>(
                          std::chrono::steady_clock::now() - start).count();
  }
  solution_ = solution;
  first_node_ = nodes.empty() ? nullptr : nodes.front();
  drawn_nodes_ = nodes.size();
}

}  // namespace node
}  // namespace hex_slam
