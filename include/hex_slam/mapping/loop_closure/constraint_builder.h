// Finds loop constraints: a node's scan matched against a finished submap by branch and bound,
// around where the pose graph expects it (local search) or anywhere on the submap (global
// search), accepted above a minimum score and refined by the front end's Gauss–Newton matcher on
// the submap's pyramid (as Cartographer's constraint builder, with Ceres's scan matcher replaced
// by ours).
//
// Not thread-safe: the loop-closure worker owns it.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_CONSTRAINT_BUILDER_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_CONSTRAINT_BUILDER_H_

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hex_slam/mapping/loop_closure/pose_graph.h"
#include "hex_slam/mapping/submap.h"
#include "hex_slam/mapping/trajectory_node.h"
#include "hex_slam/matching/fast_correlative_scan_matcher.h"
#include "hex_slam/matching/scan_matcher.h"

namespace hex_slam {
namespace mapping {

// Cartographer's constraint_builder names and meanings; defaults as there except where noted.
struct ConstraintBuilderOptions {
  // Only submaps whose origin lies this close to the node's expected position are searched.
  double max_constraint_distance = 15.0;  // m
  // The local search's half-width: this, plus search_window_growth times the path over which
  // the front end may have drifted since the graph last knew where the searched submap lay (to
  // the nearest node tied to it, one of its own or of its loop constraints, and on through
  // revisits: DriftGraph), at most matcher.linear_search_window. A window no wider than the
  // drift leaves a repeating place (a maze, a row of doors) fewer chances to look like the right
  // one. (Counted from the last loop constraint anywhere, the window stayed narrow round a whole
  // new loop, each node being matched on the submap just behind it: on the MIT Killian Court log
  // its largest loop did not close.)
  double min_linear_search_window = 0.5;  // m
  double search_window_growth = 0.05;     // m per m
  // The same for the heading, at most matcher.angular_search_window.
  double min_angular_search_window = 0.1;      // rad
  double angular_search_window_growth = 0.005;  // rad per m
  // The fraction of (node, submap) pairs within reach that are searched.
  double sampling_ratio = 0.3;
  double min_score = 0.55;
  // Global searches (MatchFullSubmap) need more: a wrong one can be anywhere.
  double global_localization_min_score = 0.6;
  // With no loop constraint for this long (s of scan time), a sampled fraction of the nodes is
  // also searched for on every finished submap, anywhere on it (Cartographer samples pairs at
  // 0.003; here nodes, each then searched on every submap).
  double global_constraint_search_after_n_seconds = 10.0;
  double global_sampling_ratio = 0.02;
  // A global match is only a candidate: one scan matched anywhere on a submap is weak evidence
  // (on the MIT Killian Court log 295 of 302 were wrong, places tens of metres off whose
  // corridors and doorways line up with the scan). It becomes a constraint once a later node,
  // between these path lengths on from it (far enough to see something else, near enough that
  // the front end's motion between them is exact), is also found by a local search on that
  // submap where the candidate puts it (Karto asks a chain of scans to agree in the same way).
  // A candidate no node confirms within the longer is dropped. 0 (the longer): taken at once.
  double global_confirm_min_distance = 1.0;   // m
  double global_confirm_max_distance = 10.0;  // m
  // The searched scan keeps consecutive endpoints at least this far apart (Cartographer thins it
  // with an adaptive voxel filter to about 100-200 points); refinement uses all of the node's.
  double point_spacing = 0.1;  // m
  // The pyramid level searched (0: finest); the refinement runs on the whole pyramid. Level 1
  // (cells twice as wide, angular steps twice as long) costs a quarter of the grids and about a
  // third of level 0's time; after refinement the optimised trajectories of the simulated mazes
  // came out within 2 mm RMSE of level 0's. Level 2 saved a fifth more of the background time
  // but left the paper's maze (robotcraft/0.01/0/1000, 1 seed) at 0.0251 m against 0.0228 m.
  int search_level = 1;
  // The level the global searches run on: every heading over the whole submap, so the coarsest
  // (at the default three levels, 4 times coarser than the finest) keeps one to tens of ms.
  int global_search_level = 2;
  // Finished submaps' pyramids and search grids kept at hand (MB); beyond it pyramids are dropped
  // first, then grids (SubmapCache), and drawn or precomputed again when needed. Most searches
  // need only the grids: on five Freiburg logs halving 256 to 128 left every relations error
  // within 0.03 mm and cost the worker 0-11 % more time (redrawing pyramids) for 5-111 MB less
  // peak memory on the four whose finished submaps outgrew 128 MB.
  double submap_cache_mb = 128.0;
  matching::FastCorrelativeScanMatcherOptions matcher;

  std::vector<std::string> Validate() const;
};

struct ConstraintSearchStats {
  long local_searches = 0;
  long global_searches = 0;
  long local_found = 0;   // scored above min_score: a constraint
  long global_found = 0;
  long ambiguous = 0;     // above the score, but another peak scored nearly as well: refused
  long candidates = 0;          // branch-and-bound bounds and poses scored
  double search_seconds = 0.0;  // branch and bound and refinement
};

template <class Lattice>
class ConstraintBuilder {
 public:
  // `refinement`: the Gauss–Newton matcher's options (the front end's).
  ConstraintBuilder(const ConstraintBuilderOptions& options,
                    const ScanMatcherOptions& refinement);

  // Searches `node` on `submap` (finished; `matcher` holds its grids) around `expected` (the
  // node's pose in the submap's frame, from the pose graph) within the windows for `distance`
  // (m of path from the node to the nearest node tied to the submap), or everywhere if
  // `global`. The constraint if one is found: Find, then Refine.
  std::optional<Constraint> Search(const Submap<Lattice>& submap,
                                   const matching::FastCorrelativeScanMatcher<Lattice>& matcher,
                                   const TrajectoryNode& node, const Pose2& expected,
                                   double distance, bool global);
  // Search's branch and bound alone, which needs the submap's grids but not its pyramid
  // (`submap_local_pose`: the frame the submap was built in). Its unambiguous match above the
  // minimum score, in the submap's grid frame.
  std::optional<matching::CorrelativeMatch> Find(
      const Pose2& submap_local_pose, const matching::FastCorrelativeScanMatcher<Lattice>& matcher,
      const TrajectoryNode& node, const Pose2& expected, double distance, bool global);
  // Search's second step: Gauss–Newton on `submap`'s pyramid from Find's `match`, and the
  // constraint.
  Constraint Refine(const Submap<Lattice>& submap, const TrajectoryNode& node,
                    const matching::CorrelativeMatch& match);
  // Where on a submap built in `submap_local_pose` (its frame) a search everywhere on it
  // (`matcher`) places `node` best, if that scores at least `min_score`, whether or not another
  // place there scores about as well: a rival to a global match on another submap. Counted as a
  // global search.
  std::optional<Pose2> BestPlace(const Pose2& submap_local_pose,
                                 const matching::FastCorrelativeScanMatcher<Lattice>& matcher,
                                 const TrajectoryNode& node, double min_score);
  // The local search's half-widths (m, rad) for `distance` (m of path over which the front end
  // may have drifted from the submap).
  double LinearWindow(double distance) const;
  double AngularWindow(double distance) const;
  // The distance (m of path) from which neither window grows any more.
  double WindowsFullFrom() const;

  const ConstraintSearchStats& stats() const { return stats_; }

 private:
  ConstraintBuilderOptions options_;
  ScanMatcherOptions refinement_;
  ConstraintSearchStats stats_;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_CONSTRAINT_BUILDER_H_
