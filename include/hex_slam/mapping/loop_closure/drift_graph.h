// How far the front end may have drifted between two parts of the trajectory, as path length
// (m), for sizing loop closure's local search windows.
//
// Submaps are the vertices. Consecutive submaps are joined by the path between their first nodes:
// the front end's drift grows along the trajectory. A revisit (a loop constraint between a node and
// a submap the path left long before, once an optimisation has taken it in) ties the node's own
// submaps to the revisited one at no cost: the graph now knows where one lies from the other. So
// after a loop closes, the drift back to the old map is counted from the revisited place along the
// old trajectory, and parts of the old map that no revisit tied stay as far as their path says,
// however many revisits happened elsewhere. (Counting from the last revisit anywhere instead, the
// widest loop on the MIT Killian Court log closed or not depending on where its drift happened to
// be.)
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_DRIFT_GRAPH_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_DRIFT_GRAPH_H_

#include <vector>

namespace hex_slam {
namespace mapping {

class DriftGraph {
 public:
  // Paths are counted up to `horizon` (m) and reported as at most it: the search windows stop
  // growing there, so nothing beyond it changes a search, and the spread stays local.
  explicit DriftGraph(double horizon);

  // The next submap (ids consecutive from 0); `first_path`: its first node's path, not less
  // than the previous submap's.
  void AddSubmap(double first_path);
  // A revisit: a node of submap `a` matched on submap `b`.
  void Tie(int a, int b);

  // The drift path from the start to every submap, where `start[s]` is the path from the start
  // to submap `s` without passing through other submaps (+inf if none): the shortest path over
  // the graph, at most the horizon.
  std::vector<double> Spread(std::vector<double> start) const;

  int size() const { return static_cast<int>(first_paths_.size()); }
  // Changes whenever a submap or a tie is added.
  long version() const { return version_; }
  double horizon() const { return horizon_; }

 private:
  double horizon_;
  std::vector<double> first_paths_;
  std::vector<std::vector<int>> ties_;
  long version_ = 0;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_DRIFT_GRAPH_H_
