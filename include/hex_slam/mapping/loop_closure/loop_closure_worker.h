// The back end's thread: it takes nodes and finished submaps from the scan path through a queue
// (the scan path only ever holds the queue's lock to push; it never waits for the work), adds
// them to the pose graph, searches loop constraints (ConstraintBuilder) and optimises every
// optimize_every_n_nodes nodes, publishing each solution on a LatestSolution board.
//
// Jobs are done one at a time in the order they were queued, and every decision (which pairs are
// searched, where from, when to optimise) depends only on that order, never on timing: the same
// scans give the same solution, whether the worker kept up or ran behind.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_WORKER_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_WORKER_H_

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hex_slam/mapping/loop_closure/constraint_builder.h"
#include "hex_slam/mapping/loop_closure/drift_graph.h"
#include "hex_slam/mapping/loop_closure/fixed_ratio_sampler.h"
#include "hex_slam/mapping/loop_closure/loop_closure_options.h"
#include "hex_slam/mapping/loop_closure/pose_graph.h"
#include "hex_slam/mapping/loop_closure/pose_graph_solution.h"
#include "hex_slam/mapping/submap.h"
#include "hex_slam/mapping/loop_closure/submap_cache.h"
#include "hex_slam/mapping/trajectory_node.h"

namespace hex_slam {
namespace mapping {

struct LoopClosureStats {
  int nodes = 0;
  int submaps = 0;
  int finished_submaps = 0;
  ConstraintSearchStats search;
  // Added to the graph: local ones as found, global ones once a later node confirmed them.
  int loop_constraints = 0;
  int global_confirmed = 0;    // global candidates a later node confirmed (both went in)
  int global_unconfirmed = 0;  // dropped: no node within the confirming distance agreed
  // Dropped at once: another submap's match placed the node elsewhere, scoring nearly as well
  // (all the node's candidates) or less well (that one).
  int global_rivals = 0;
  // Of those, how many the latest optimisation left consistent with the solution (within two
  // finest cells and two degrees); the rest the Huber loss overruled.
  int loop_constraints_consistent = 0;
  // The nodes found slipped so far, their front end's constraints made robust
  // (PoseGraphOptions::slip_distance).
  int slipped_nodes = 0;
  int optimizations = 0;
  double optimization_seconds = 0.0;       // all of them
  double last_optimization_seconds = 0.0;
  double busy_seconds = 0.0;  // the worker's time on jobs, searches and optimisations included
  // Of it, the CPU time the worker's thread got: busy_seconds less the time the thread waited
  // for a core (it runs below the scan path). What the work costs, whatever the machine's load.
  double cpu_seconds = 0.0;
  std::size_t queued = 0;      // jobs waiting now
  std::size_t max_queued = 0;  // the most that ever waited
  std::size_t cached_submap_bytes = 0;  // the most the SubmapCache held at once
  long search_grids_built = 0;          // branch-and-bound precomputations
  long submaps_redrawn = 0;             // finished submaps drawn again from their nodes
  long pyramids_not_queued = 0;  // finished submaps queued without them (worker behind)
  std::string first_error;  // of the first job that failed (it was dropped); empty if none
};

template <class Lattice>
class LoopClosureWorker {
 public:
  // `refinement`: the front end's Gauss–Newton options, for refining loop constraints; `grid`:
  // how submaps are drawn, for drawing finished ones again.
  LoopClosureWorker(const LoopClosureOptions& options, const ScanMatcherOptions& refinement,
                    const SubmapGridParameters& grid, std::shared_ptr<LatestSolution> board);
  // Stops after the job in hand; queued jobs are dropped.
  ~LoopClosureWorker();
  LoopClosureWorker(const LoopClosureWorker&) = delete;
  LoopClosureWorker& operator=(const LoopClosureWorker&) = delete;

  // A new node and the submaps (id, frame in the local frame) it was inserted into; ids are
  // consecutive from 0 in both cases. Returns at once.
  void AddNode(std::shared_ptr<const TrajectoryNode> node,
               std::vector<std::pair<int, Pose2>> submaps);
  // A submap that will not change any more. Returns at once, or once the worker has taken
  // enough of the queued ones (LoopClosureOptions::max_queued_submaps).
  void AddFinishedSubmap(std::shared_ptr<Submap<Lattice>> submap);
  // Blocks until every job queued so far is done and one more optimisation has been published.
  void Flush();

  LoopClosureStats stats() const;

 private:
  struct Job {
    enum class Kind { kNode, kSubmap, kFlush } kind = Kind::kNode;
    std::shared_ptr<const TrajectoryNode> node;
    std::vector<std::pair<int, Pose2>> submaps;
    // Finished: the worker's alone from now on, or null when it was queued without its
    // pyramid (LoopClosureOptions::max_queued_submap_pyramids).
    std::shared_ptr<Submap<Lattice>> submap;
    int submap_id = 0;
    std::uint64_t ticket = 0;
  };
  struct NodeRecord {
    std::shared_ptr<const TrajectoryNode> node;
    std::vector<int> submaps;
    double path = 0.0;  // m the front end travelled from the first node to this one
  };
  // A global match waiting for a later node to confirm it (ConstraintBuilderOptions).
  struct GlobalCandidate {
    Constraint constraint;
    Pose2 correction;  // what it makes of the graph's pose of its node: implied * pose^-1
    double path = 0.0;  // the node's
  };
  struct SubmapRecord {
    Pose2 local_pose;
    bool finished = false;  // false while the front end builds it
    FixedRatioSampler sampler;
    std::vector<int> nodes;  // inserted into it, in order
    std::vector<int> loop_nodes;  // of its loop constraints
  };

  void Push(Job job);
  void Run();
  void Process(const Job& job);
  void ProcessNode(const Job& job);
  // `submap` may be null: queued without its pyramid, it is drawn again when searched.
  void ProcessFinishedSubmap(int id, std::shared_ptr<Submap<Lattice>> submap);
  // Searches node `n` on finished submap `s` (not its own): locally if they are near (sampled),
  // or everywhere on it if `global`. Returns whether a loop constraint was added.
  bool MaybeSearch(int n, int s, bool global);
  // ConstraintBuilder::Search of node `n` on finished submap `s` around `expected` (the node in
  // the submap's frame), with the grids from the cache and the pyramid drawn only to refine.
  std::optional<Constraint> Search(int n, int s, const Pose2& expected, double distance,
                                   bool global);
  // Node `n` (the newest) tries to confirm the waiting global candidates; drops those it has
  // driven past.
  void ConfirmCandidates(int n);
  // Node `n`'s global candidates (one per submap its search found it on) are one hypothesis or
  // rivals: keeps those that place the node where the best-scoring one does, and drops them all
  // when one placing it elsewhere scores nearly as well (the branch-and-bound matcher's
  // ambiguity_ratio, across submaps).
  void SettleRivalCandidates(int n);
  // Whether anything places node `n` far from `placed` (FarApart) with at least `min_score`: one
  // of its global candidates, or the best place on another finished submap.
  bool RivalPlaces(int n, const Pose2& placed, double min_score);
  void AddLoopConstraint(const Constraint& constraint);
  // How far (m of path) node `n` is from the nearest node tied to submap `s` (its own or a loop
  // constraint's): the front end may have drifted by a fraction of it since the graph last knew
  // where `s` lay.
  double UntiedPath(int n, int s) const;
  // The path (m) over which the front end may have drifted from submap `s` when node `n` is
  // searched on it: UntiedPath to some submap, then on over the DriftGraph to `s`.
  double DriftPath(int n, int s);
  // Whether two poses of a node on a submap agree as a correct match's would.
  bool Consistent(const Pose2& a, const Pose2& b) const;
  // Whether two poses of a node are farther apart than the widest local search window: two
  // places, not one place seen through drift.
  bool FarApart(const Pose2& a, const Pose2& b) const;
  // Finished submap `s`, its pyramid drawn again from its nodes if the cache had dropped it.
  std::shared_ptr<const Submap<Lattice>> Hydrated(int s);
  // Finished submap `s`'s branch-and-bound grids for local or global searches, precomputed
  // again (from Hydrated) if the cache had dropped them.
  std::shared_ptr<const typename SubmapCache<Lattice>::Matcher> SearchGrids(int s, bool global);
  // After a solved optimisation: ties in the DriftGraph the revisits it left consistent.
  void TieRevisits();
  void Optimize();

  LoopClosureOptions options_;
  SubmapGridParameters grid_;
  std::shared_ptr<LatestSolution> board_;

  // The worker thread's own state.
  PoseGraph graph_;
  ConstraintBuilder<Lattice> builder_;
  SubmapCache<Lattice> cache_;
  long submaps_redrawn_ = 0;
  std::vector<NodeRecord> nodes_;
  std::vector<SubmapRecord> submaps_;
  Pose2 correction_;
  FixedRatioSampler global_sampler_;
  double last_loop_stamp_ = 0.0;
  DriftGraph drift_;
  std::vector<Constraint> pending_revisits_;  // since the last optimisation
  // DriftGraph::Spread from one submap, kept while the graph is unchanged: a finished submap is
  // searched for many older nodes in a row.
  int spread_source_ = -1;
  long spread_version_ = -1;
  std::vector<double> spread_;
  int nodes_since_optimization_ = 0;
  std::vector<GlobalCandidate> candidates_;

  mutable std::mutex mutex_;  // guards the queue, the tickets and stats_
  std::condition_variable wake_;
  std::condition_variable flushed_;
  std::condition_variable submap_taken_;  // the scan path waits on it (max_queued_submaps)
  int queued_submaps_ = 0;
  int queued_pyramids_ = 0;  // queued finished submaps that hold theirs
  std::deque<Job> queue_;
  bool stop_ = false;
  std::uint64_t tickets_issued_ = 0;
  std::uint64_t tickets_done_ = 0;
  LoopClosureStats stats_;
  std::thread thread_;  // last: starts once everything above exists
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_WORKER_H_
