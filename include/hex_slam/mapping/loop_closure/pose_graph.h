// The 2D pose graph of the back end (sparse pose adjustment, as Cartographer's): submaps and
// nodes (inserted scans), each an (x, y, θ) pose in the global frame, tied by relative-pose
// constraints "node j seen from submap i". Local constraints come from the front end (the node
// was inserted into the submap at that pose); loop constraints from scan matching a node against
// a finished submap, under a Huber loss so a wrong one cannot drag the whole map. Consecutive
// nodes are also tied by the front end's motion between them (Cartographer's local SLAM pose
// constraints), which keeps the trajectory locally as the front end saw it while loop
// constraints bend it at large. Solved with Ceres; the first submap is held fixed, which fixes
// the gauge.
//
// Not thread-safe: the loop-closure worker owns it.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_POSE_GRAPH_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_POSE_GRAPH_H_

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace mapping {

enum class ConstraintTag {
  kLocal,  // the front end inserted the node into the submap (Cartographer's INTRA_SUBMAP)
  kLoop,   // found by the constraint search (INTER_SUBMAP)
};

struct Constraint {
  int submap = 0;  // id
  int node = 0;    // id
  Pose2 relative;  // the node's pose in the submap's frame: submap⁻¹ · node
  ConstraintTag tag = ConstraintTag::kLocal;
  double score = 0.0;  // a loop constraint's correlative score (0 for local ones)
};

// The front end's motion from node `previous` to node `next`: previous⁻¹ · next.
struct ConsecutiveConstraint {
  int previous = 0;
  int next = 0;
  Pose2 relative;
};

// Cartographer's weights (pose_graph.optimization_problem and constraint_builder): they scale the
// residuals, metres and radians, so only their ratios and the Huber scale matter. Weighting the
// local constraints 10 times more (trusting the front end's placement of a node in its own submap
// more) helps where the front end hardly drifts (the paper's maze: the optimised trajectory as
// good as the front end's own instead of 20-40% worse) but hurts where it drifts 1% of the
// distance (the pose graph test's drive: 0.11-0.31 m RMSE left instead of 0.05-0.08 m), the
// case loop closure is for; so Cartographer's are kept, but for the consecutive translation weight.
struct PoseGraphOptions {
  double local_translation_weight = 5e2;    // Cartographer: matcher_translation_weight
  double local_rotation_weight = 1.6e3;     // matcher_rotation_weight
  double loop_translation_weight = 1.1e4;   // loop_closure_translation_weight
  double loop_rotation_weight = 1e5;        // loop_closure_rotation_weight
  // Cartographer weighs it 1e5, ten times a loop constraint's translation (a node's motion known
  // ten times better than where a loop match puts it). Here both rest on one scan matched on a
  // submap, which MatchCovariance puts at millimetres (Intel's loop matches: median 2.4 and
  // 4.9 mm along the axes); weighed alike, loop constraints bend the front end's path where it
  // drifted instead of moving long stretches of it rigidly. Intel's relations 0.01622 -> 0.01561 m
  // (odometry), 0.01641 -> 0.01592 m (none); the simulated building loop 0.047/0.029/0.034 ->
  // 0.042/0.026/0.027 m RMSE (seeds 1-3); the paper's maze 0.0228 -> 0.0225 m. (5e3 and 3e4
  // gave about the same; 1e3 for it and the rotation weight was worse.)
  double consecutive_translation_weight = 1.1e4;  // local_slam_pose_translation_weight
  double consecutive_rotation_weight = 1e5;     // local_slam_pose_rotation_weight
  // Huber loss on loop constraints' weighted residuals: quadratic below this, linear above.
  // 0 disables it (least squares).
  double huber_scale = 1e1;
  // A node the front end slipped: two of its loop constraints, on submaps no node shares, place it
  // within slip_distance and slip_angle of each other, and the solution leaves it farther than
  // slip_distance from both. The consecutive constraints hold it there: at Cartographer's weights a
  // loop constraint's pull stops growing once it is off by a millimetre (huber_scale /
  // loop_translation_weight) while theirs grows with the error, so no handful of loop constraints
  // moves a node its front end put centimetres off. (The Intel subset without odometry: while the
  // robot spins at a corridor junction the matches wander along the corridor and four nodes are
  // inserted 0.18-0.26 m off; two of them have loop constraints on two later submaps that agree to
  // 4 mm on where they were.) Such a node's consecutive constraints get the loop constraints' Huber
  // loss, as do its local constraints (they carry the slip too), and the graph is solved again from
  // the solution. Two independent submaps agreeing is the evidence: one loop constraint, or two on
  // submaps that share scans (and so their errors), leave the node where its front end put it. So
  // does a slip not bounded by nodes the loop constraints confirm: the nearest node before it and
  // after it with loop constraints (and not slipped itself) must have all of them within these of
  // the solution; otherwise the whole stretch is offset from an older pass, not slipped, and moving
  // the few nodes with two agreeing constraints would kink the path. A node found slipped stays
  // so in later optimisations. 0: never.
  double slip_distance = 0.1;              // m, two finest cells at the default resolution
  double slip_angle = 2.0 * M_PI / 180.0;  // rad
  int max_num_iterations = 50;

  std::vector<std::string> Validate() const;
};

struct OptimizationSummary {
  bool solved = false;  // Ceres reported a usable solution and every pose stayed finite
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  double seconds = 0.0;
  int slipped_nodes = 0;  // found so (slip_distance), by this optimisation or an earlier one
  std::string message;  // Ceres's brief report when not solved
};

class PoseGraph {
 public:
  explicit PoseGraph(const PoseGraphOptions& options);

  // Ids are consecutive from 0 in the order of addition; the pose is the initial estimate.
  int AddSubmap(const Pose2& global_pose);
  int AddNode(const Pose2& global_pose);
  // Both ends must exist (throws std::out_of_range otherwise).
  void AddConstraint(const Constraint& constraint);
  void AddConsecutiveConstraint(const ConsecutiveConstraint& constraint);

  // Adjusts every pose but the first submap's. On failure the poses are left as they were.
  OptimizationSummary Optimize();

  const std::vector<Pose2>& submap_poses() const { return submaps_; }
  const std::vector<Pose2>& node_poses() const { return nodes_; }
  const std::vector<Constraint>& constraints() const { return constraints_; }
  const std::vector<ConsecutiveConstraint>& consecutive_constraints() const {
    return consecutive_;
  }
  const PoseGraphOptions& options() const { return options_; }

 private:
  PoseGraphOptions options_;
  std::vector<Pose2> submaps_;
  std::vector<Pose2> nodes_;
  std::vector<bool> slipped_;  // by node id, found so by an optimisation (slip_distance)
  std::vector<Constraint> constraints_;
  std::vector<ConsecutiveConstraint> consecutive_;
};

// The weighted residual of `constraint` at the given poses (translation in the submap's frame,
// then the angle), as the optimisation sees it.
Eigen::Vector3d ConstraintResidual(const Constraint& constraint, const Pose2& submap,
                                   const Pose2& node, double translation_weight,
                                   double rotation_weight);

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_POSE_GRAPH_H_
