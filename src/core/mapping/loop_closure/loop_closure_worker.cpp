#include "hex_slam/mapping/loop_closure/loop_closure_worker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "hex_slam/common/thread_clock.h"
#include "hex_slam/common/thread_priority.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {
namespace {

// Two estimates of a node's pose on a submap agree (a loop constraint with a solution, a global
// candidate with the node that confirms it) within this many finest cells and this angle: what
// a correct match's error is, far below a wrong one's.
constexpr double kConsistentTranslationCells = 2.0;
constexpr double kConsistentRotation = 2.0 * M_PI / 180.0;  // rad
constexpr double kBytesPerMb = 1e6;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

template <class Lattice>
LoopClosureWorker<Lattice>::LoopClosureWorker(const LoopClosureOptions& options,
                                              const ScanMatcherOptions& refinement,
                                              const SubmapGridParameters& grid,
                                              std::shared_ptr<LatestSolution> board)
    : options_(options),
      grid_(grid),
      board_(std::move(board)),
      graph_(options.pose_graph),
      builder_(options.constraints, refinement),
      cache_(static_cast<std::size_t>(options.constraints.submap_cache_mb * kBytesPerMb),
             options.constraints.matcher, options.constraints.search_level,
             options.constraints.global_search_level),
      global_sampler_(options.constraints.global_sampling_ratio),
      drift_(builder_.WindowsFullFrom()),
      thread_(&LoopClosureWorker::Run, this) {}

template <class Lattice>
LoopClosureWorker<Lattice>::~LoopClosureWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
    queued_submaps_ = queued_pyramids_ = 0;
  }
  wake_.notify_all();
  submap_taken_.notify_all();
  thread_.join();
}

template <class Lattice>
void LoopClosureWorker<Lattice>::Push(Job job) {
  // Only a flush, which its caller waits for, wakes the worker; nodes and finished submaps wait
  // for its next look (kBackgroundPollPeriod): waking it would be a system call on the scan path.
  const bool wake = job.kind == Job::Kind::kFlush;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (job.kind == Job::Kind::kSubmap) {
      ++queued_submaps_;
      const int kept = options_.max_queued_submap_pyramids;
      if (kept >= 0 && queued_pyramids_ >= kept) {
        job.submap.reset();  // freed here: the worker draws it again from its nodes
        ++stats_.pyramids_not_queued;
      }
      if (job.submap) ++queued_pyramids_;
    }
    queue_.push_back(std::move(job));
    stats_.queued = queue_.size();
    stats_.max_queued = std::max(stats_.max_queued, queue_.size());
  }
  if (wake) wake_.notify_one();
}

template <class Lattice>
void LoopClosureWorker<Lattice>::AddNode(std::shared_ptr<const TrajectoryNode> node,
                                         std::vector<std::pair<int, Pose2>> submaps) {
  Job job;
  job.kind = Job::Kind::kNode;
  job.node = std::move(node);
  job.submaps = std::move(submaps);
  Push(std::move(job));
}

template <class Lattice>
void LoopClosureWorker<Lattice>::AddFinishedSubmap(std::shared_ptr<Submap<Lattice>> submap) {
  Job job;
  job.kind = Job::Kind::kSubmap;
  job.submap_id = submap->id();
  job.submap = std::move(submap);
  if (options_.max_queued_submaps > 0) {
    std::unique_lock<std::mutex> lock(mutex_);
    submap_taken_.wait(lock, [this] {
      return stop_ || queued_submaps_ < options_.max_queued_submaps;
    });
  }
  Push(std::move(job));
}

template <class Lattice>
void LoopClosureWorker<Lattice>::Flush() {
  Job job;
  job.kind = Job::Kind::kFlush;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job.ticket = ++tickets_issued_;
  }
  const std::uint64_t ticket = job.ticket;
  Push(std::move(job));
  std::unique_lock<std::mutex> lock(mutex_);
  flushed_.wait(lock, [this, ticket] { return tickets_done_ >= ticket || stop_; });
}

template <class Lattice>
LoopClosureStats LoopClosureWorker<Lattice>::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

template <class Lattice>
void LoopClosureWorker<Lattice>::Run() {
  // Below the scan path (LoopClosureOptions::worker_niceness; in the node also below its map
  // thread, whose redraws wait for the worker's solutions anyway).
  if (options_.worker_idle_priority) {
    MakeThisThreadIdle();
  } else if (options_.worker_niceness > 0) {
    LowerThisThreadPriority(options_.worker_niceness);
  }
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      const auto work = [this] { return stop_ || !queue_.empty(); };
      while (!wake_.wait_for(lock, kBackgroundPollPeriod, work)) {
      }
      if (stop_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      stats_.queued = queue_.size();
      if (job.kind == Job::Kind::kSubmap) --queued_submaps_;
      if (job.submap) --queued_pyramids_;
    }
    if (job.kind == Job::Kind::kSubmap) submap_taken_.notify_all();
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = ThreadCpuSeconds();
    std::string error;
    try {
      Process(job);
    } catch (const std::exception& e) {
      // A job that fails is dropped (and said so); the graph keeps what it had.
      error = e.what();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error.empty() && stats_.first_error.empty()) stats_.first_error = error;
    stats_.busy_seconds += Seconds(start);
    stats_.cpu_seconds += ThreadCpuSeconds() - cpu_start;
    stats_.search = builder_.stats();
    stats_.cached_submap_bytes = std::max(stats_.cached_submap_bytes, cache_.bytes());
    stats_.search_grids_built = cache_.matchers_built();
    stats_.submaps_redrawn = submaps_redrawn_;
    if (job.kind == Job::Kind::kFlush) {
      tickets_done_ = job.ticket;
      flushed_.notify_all();
    }
  }
}

template <class Lattice>
void LoopClosureWorker<Lattice>::Process(const Job& job) {
  switch (job.kind) {
    case Job::Kind::kNode:
      ProcessNode(job);
      if (++nodes_since_optimization_ >= options_.optimize_every_n_nodes) Optimize();
      break;
    case Job::Kind::kSubmap:
      ProcessFinishedSubmap(job.submap_id, job.submap);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        ++stats_.finished_submaps;
      }
      break;
    case Job::Kind::kFlush:
      Optimize();
      // The trajectory is finished (LoopClosure::FinishTrajectory): nothing is searched again
      // until new nodes come, when the submaps are drawn again. An offline run draws the map
      // and writes its files next, and the cache's budget of memory is best given back to that.
      cache_.Clear();
      break;
  }
}

template <class Lattice>
void LoopClosureWorker<Lattice>::ProcessNode(const Job& job) {
  const TrajectoryNode& node = *job.node;
  if (node.id != static_cast<int>(nodes_.size())) {
    throw std::logic_error("loop closure: node " + std::to_string(node.id) + " arrived out of order");
  }
  NodeRecord record{job.node, {}};
  std::optional<Pose2> motion;
  if (!nodes_.empty()) {
    motion = RelativePose(nodes_.back().node->local_pose, node.local_pose);
    record.path = nodes_.back().path + motion->translation().norm();
  }
  for (const auto& [id, local_pose] : job.submaps) {
    if (id == static_cast<int>(submaps_.size())) {
      graph_.AddSubmap(correction_ * local_pose);
      drift_.AddSubmap(record.path);
      submaps_.push_back(
          {local_pose, false, FixedRatioSampler(options_.constraints.sampling_ratio), {}, {}});
    } else if (id > static_cast<int>(submaps_.size())) {
      throw std::logic_error("loop closure: submap " + std::to_string(id) + " arrived out of order");
    }
    record.submaps.push_back(id);
  }
  graph_.AddNode(correction_ * node.local_pose);
  for (const int s : record.submaps) {
    graph_.AddConstraint({s, node.id, RelativePose(submaps_[s].local_pose, node.local_pose),
                          ConstraintTag::kLocal, 0.0});
    submaps_[s].nodes.push_back(node.id);
  }
  if (motion) graph_.AddConsecutiveConstraint({node.id - 1, node.id, *motion});
  if (nodes_.empty()) last_loop_stamp_ = node.stamp;
  nodes_.push_back(std::move(record));
  ConfirmCandidates(node.id);
  bool found = false;
  for (int s = 0; s < static_cast<int>(submaps_.size()); ++s) {
    found = MaybeSearch(node.id, s, false) || found;
  }
  // After a while without any loop constraint the drift may exceed every local window: a
  // sampled node is then also searched everywhere on every submap.
  const bool due = node.stamp - last_loop_stamp_ >
                   options_.constraints.global_constraint_search_after_n_seconds;
  if (!found && due && global_sampler_.Pulse()) {
    for (int s = 0; s < static_cast<int>(submaps_.size()); ++s) MaybeSearch(node.id, s, true);
    SettleRivalCandidates(node.id);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  stats_.nodes = static_cast<int>(nodes_.size());
  stats_.submaps = static_cast<int>(submaps_.size());
}

template <class Lattice>
void LoopClosureWorker<Lattice>::ProcessFinishedSubmap(int s,
                                                       std::shared_ptr<Submap<Lattice>> submap) {
  if (s >= static_cast<int>(submaps_.size())) {
    throw std::logic_error("loop closure: submap " + std::to_string(s) + " finished unseen");
  }
  // The older nodes are searched on it now, the newer ones as they come.
  submaps_[s].finished = true;
  if (submap) {
    // Its storage was reserved for scans it may not have got: the cache holds what it covers.
    submap->ShrinkToWritten();
    if (!cache_.FindMaps(s)) cache_.AddMaps(std::move(submap));
  }
  for (int n = 0; n < static_cast<int>(nodes_.size()); ++n) MaybeSearch(n, s, false);
}

template <class Lattice>
std::shared_ptr<const Submap<Lattice>> LoopClosureWorker<Lattice>::Hydrated(int s) {
  if (std::shared_ptr<const Submap<Lattice>> held = cache_.FindMaps(s)) return held;
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  for (const int n : submaps_[s].nodes) nodes.push_back(nodes_[n].node);
  ++submaps_redrawn_;
  std::shared_ptr<const Submap<Lattice>> drawn =
      Submap<Lattice>::FromNodes(s, submaps_[s].local_pose, grid_, nodes);
  cache_.AddMaps(drawn);
  return drawn;
}

template <class Lattice>
std::shared_ptr<const typename SubmapCache<Lattice>::Matcher>
LoopClosureWorker<Lattice>::SearchGrids(int s, bool global) {
  if (auto held = cache_.FindMatcher(s, global)) return held;
  return cache_.AddMatcher(*Hydrated(s), global);
}

template <class Lattice>
bool LoopClosureWorker<Lattice>::MaybeSearch(int n, int s, bool global) {
  SubmapRecord& submap = submaps_[s];
  if (!submap.finished) return false;
  const NodeRecord& record = nodes_[n];
  for (const int own : record.submaps) {
    if (own == s) return false;
  }
  const Pose2& submap_pose = graph_.submap_poses()[s];
  const Pose2& node_pose = graph_.node_poses()[n];
  if (!global) {
    // Near submaps are searched around where the graph expects the node, sampled.
    const double distance = (node_pose.translation() - submap_pose.translation()).norm();
    if (distance > options_.constraints.max_constraint_distance || !submap.sampler.Pulse()) {
      return false;
    }
  }
  const std::optional<Constraint> found =
      Search(n, s, RelativePose(submap_pose, node_pose), DriftPath(n, s), global);
  if (!found) return false;
  if (global && options_.constraints.global_confirm_max_distance > 0.0) {
    const Pose2 implied = submap_pose * found->relative;
    candidates_.push_back({*found, implied * node_pose.inverse(), record.path});
    return false;
  }
  AddLoopConstraint(*found);
  return true;
}

template <class Lattice>
std::optional<Constraint> LoopClosureWorker<Lattice>::Search(int n, int s, const Pose2& expected,
                                                             double distance, bool global) {
  // The pyramid is drawn only for a match to refine: most searches find none.
  const TrajectoryNode& node = *nodes_[n].node;
  const std::optional<matching::CorrelativeMatch> match = builder_.Find(
      submaps_[s].local_pose, *SearchGrids(s, global), node, expected, distance, global);
  if (!match) return std::nullopt;
  return builder_.Refine(*Hydrated(s), node, *match);
}

template <class Lattice>
void LoopClosureWorker<Lattice>::ConfirmCandidates(int n) {
  const ConstraintBuilderOptions& o = options_.constraints;
  const NodeRecord& record = nodes_[n];
  std::vector<GlobalCandidate> waiting;
  for (const GlobalCandidate& candidate : candidates_) {
    const double travelled = record.path - candidate.path;
    if (travelled > o.global_confirm_max_distance) {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.global_unconfirmed;
      continue;
    }
    // (A candidate's submap was finished before this node came: it is never the node's own.)
    const int s = candidate.constraint.submap;
    if (travelled < o.global_confirm_min_distance) {
      waiting.push_back(candidate);
      continue;
    }
    // Where the candidate puts this node: its graph pose moved as the candidate moves its own.
    const Pose2 expected = RelativePose(graph_.submap_poses()[s],
                                        candidate.correction * graph_.node_poses()[n]);
    const std::optional<Constraint> agrees = Search(n, s, expected, 0.0, false);
    // Found near where the candidate says is not enough (in a corridor the walls alone score
    // well a little off); the front end's motion since is exact to a few cm, so it must be there.
    if (!agrees || !Consistent(expected, agrees->relative)) {
      waiting.push_back(candidate);
      continue;
    }
    AddLoopConstraint(candidate.constraint);
    AddLoopConstraint(*agrees);
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.global_confirmed;
  }
  candidates_ = std::move(waiting);
}

template <class Lattice>
void LoopClosureWorker<Lattice>::SettleRivalCandidates(int n) {
  const auto own = [n](const GlobalCandidate& c) { return c.constraint.node == n; };
  const GlobalCandidate* best = nullptr;
  for (const GlobalCandidate& c : candidates_) {
    if (own(c) && (!best || c.constraint.score > best->constraint.score)) best = &c;
  }
  if (!best) return;
  const Pose2 node_pose = graph_.node_poses()[n];
  const Pose2 placed = best->correction * node_pose;
  const bool ambiguous = RivalPlaces(
      n, placed, options_.constraints.matcher.ambiguity_ratio * best->constraint.score);
  const auto dropped = [&](const GlobalCandidate& c) {
    return own(c) && (ambiguous || FarApart(placed, c.correction * node_pose));
  };
  const long count = std::count_if(candidates_.begin(), candidates_.end(), dropped);
  candidates_.erase(std::remove_if(candidates_.begin(), candidates_.end(), dropped),
                    candidates_.end());
  std::lock_guard<std::mutex> lock(mutex_);
  stats_.global_rivals += static_cast<int>(count);
}

template <class Lattice>
bool LoopClosureWorker<Lattice>::RivalPlaces(int n, const Pose2& placed, double min_score) {
  const Pose2 node_pose = graph_.node_poses()[n];
  std::vector<bool> searched(submaps_.size(), false);
  for (const int s : nodes_[n].submaps) searched[s] = true;
  for (const GlobalCandidate& c : candidates_) {
    if (c.constraint.node != n) continue;
    searched[c.constraint.submap] = true;
    if (c.constraint.score >= min_score && FarApart(placed, c.correction * node_pose)) {
      return true;
    }
  }
  // As within a submap, a rival counts below the minimum score: the other finished submaps are
  // searched again down to min_score.
  for (int s = 0; s < static_cast<int>(submaps_.size()); ++s) {
    if (searched[s] || !submaps_[s].finished) continue;
    const std::optional<Pose2> place = builder_.BestPlace(
        submaps_[s].local_pose, *SearchGrids(s, true), *nodes_[n].node, min_score);
    if (place && FarApart(placed, graph_.submap_poses()[s] * *place)) return true;
  }
  return false;
}

template <class Lattice>
bool LoopClosureWorker<Lattice>::FarApart(const Pose2& a, const Pose2& b) const {
  // Two right matches of a node on different submaps place it apart by at most the drift
  // between those submaps that the graph has not yet corrected, which a local search covers.
  const matching::FastCorrelativeScanMatcherOptions& window = options_.constraints.matcher;
  const Pose2 apart = RelativePose(a, b);
  return apart.translation().norm() > window.linear_search_window ||
         std::abs(apart.theta) > window.angular_search_window;
}

template <class Lattice>
double LoopClosureWorker<Lattice>::UntiedPath(int n, int s) const {
  const double path = nodes_[n].path;
  const SubmapRecord& submap = submaps_[s];
  // Its own nodes came in order: their paths span one interval.
  const double first = nodes_[submap.nodes.front()].path;
  const double last = nodes_[submap.nodes.back()].path;
  double nearest = std::max({0.0, first - path, path - last});
  for (const int m : submap.loop_nodes) nearest = std::min(nearest, std::abs(path - nodes_[m].path));
  return nearest;
}

template <class Lattice>
double LoopClosureWorker<Lattice>::DriftPath(int n, int s) {
  if (spread_source_ != s || spread_version_ != drift_.version()) {
    std::vector<double> start(submaps_.size(), std::numeric_limits<double>::infinity());
    start[s] = 0.0;
    spread_ = drift_.Spread(std::move(start));
    spread_source_ = s;
    spread_version_ = drift_.version();
  }
  double drift = drift_.horizon();
  for (int t = 0; t < static_cast<int>(submaps_.size()); ++t) {
    if (spread_[t] < drift) drift = std::min(drift, spread_[t] + UntiedPath(n, t));
  }
  return drift;
}

template <class Lattice>
bool LoopClosureWorker<Lattice>::Consistent(const Pose2& a, const Pose2& b) const {
  const Pose2 error = RelativePose(a, b);
  return error.translation().norm() <= kConsistentTranslationCells * grid_.finest_spacing &&
         std::abs(error.theta) <= kConsistentRotation;
}

template <class Lattice>
void LoopClosureWorker<Lattice>::AddLoopConstraint(const Constraint& constraint) {
  graph_.AddConstraint(constraint);
  last_loop_stamp_ = std::max(last_loop_stamp_, nodes_[constraint.node].node->stamp);
  // Only a revisit ties (the submap untied for more path than doubles the narrowest window): a
  // match on a submap the front end left a short way back restates its drift rather than
  // removing it, and such ties, chained submap to submap along a lap, would make the whole
  // trajectory look tied.
  const ConstraintBuilderOptions& o = options_.constraints;
  const double revisit = o.search_window_growth > 0.0
                             ? o.min_linear_search_window / o.search_window_growth
                             : std::numeric_limits<double>::infinity();
  if (UntiedPath(constraint.node, constraint.submap) > revisit) {
    pending_revisits_.push_back(constraint);
  }
  submaps_[constraint.submap].loop_nodes.push_back(constraint.node);
  std::lock_guard<std::mutex> lock(mutex_);
  ++stats_.loop_constraints;
}

template <class Lattice>
void LoopClosureWorker<Lattice>::TieRevisits() {
  // Until the graph has moved the nodes by a revisit, they are expected where the drift left
  // them; and one the robust loss overruled (a wrong match, or one the rest of the graph
  // disputes) tells nothing of where the submaps lie. Either would narrow windows around a
  // wrong expectation.
  for (const Constraint& c : pending_revisits_) {
    const Pose2 solved =
        RelativePose(graph_.submap_poses()[c.submap], graph_.node_poses()[c.node]);
    if (!Consistent(c.relative, solved)) continue;
    for (const int own : nodes_[c.node].submaps) drift_.Tie(own, c.submap);
  }
  pending_revisits_.clear();
}

template <class Lattice>
void LoopClosureWorker<Lattice>::Optimize() {
  nodes_since_optimization_ = 0;
  if (nodes_.empty()) return;
  const OptimizationSummary summary = graph_.Optimize();
  if (summary.solved) {
    TieRevisits();
    const TrajectoryNode& newest = *nodes_.back().node;
    correction_ = graph_.node_poses().back() * newest.local_pose.inverse();
  }
  PoseGraphSolution solution;
  solution.correction = correction_;
  solution.node_poses = graph_.node_poses();
  solution.submap_poses = graph_.submap_poses();
  solution.nodes.reserve(nodes_.size());
  for (const NodeRecord& r : nodes_) solution.nodes.push_back(r.node);
  for (const SubmapRecord& r : submaps_) solution.submap_local_poses.push_back(r.local_pose);
  solution.constraints = graph_.constraints();
  int consistent = 0;
  for (const Constraint& c : graph_.constraints()) {
    if (c.tag == ConstraintTag::kLoop) {
      ++solution.loop_constraints;
      if (Consistent(c.relative,
                     RelativePose(solution.submap_poses[c.submap], solution.node_poses[c.node]))) {
        ++consistent;
      }
    } else {
      ++solution.local_constraints;
    }
  }
  board_->Publish(std::move(solution));
  std::lock_guard<std::mutex> lock(mutex_);
  ++stats_.optimizations;
  stats_.optimization_seconds += summary.seconds;
  stats_.last_optimization_seconds = summary.seconds;
  stats_.loop_constraints_consistent = consistent;
  if (summary.solved) stats_.slipped_nodes = summary.slipped_nodes;
}

template class LoopClosureWorker<HexLattice>;
template class LoopClosureWorker<SquareLattice>;

}  // namespace mapping
}  // namespace hex_slam
