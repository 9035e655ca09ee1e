#include "hex_slam/mapping/loop_closure/pose_graph.h"

#include <cmath>
#include <random>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

namespace hex_slam {
namespace mapping {
namespace {

// Two laps of a 12 m × 8 m rectangle, a node every 0.4 m and a quarter turn in three steps at each
// corner; the front end's (local) poses drift like odometry: every step's motion is off by
// Gaussian noise and a heading bias (about 1% of the distance, as a poor front end). Submaps as the back end makes them: a new one every
// `kNodesPerSubmap` nodes, each node in the two newest, the submap's frame at its first node's
// position (heading 0), rigidly tied to that node.
constexpr int kNodesPerSubmap = 10;
constexpr double kStep = 0.4;

struct SimulatedGraph {
  std::vector<Pose2> truth;   // of each node
  std::vector<Pose2> local;   // the drifting front end's estimate
  std::vector<Pose2> submap_local;
  std::vector<Pose2> submap_truth;
  std::vector<Constraint> local_constraints;
  std::vector<int> lap;  // of each node, 0 or 1
};

std::vector<Pose2> RectangleLaps(int laps) {
  std::vector<Pose2> path;
  Pose2 pose;
  for (int lap = 0; lap < laps; ++lap) {
    for (const double side : {12.0, 8.0, 12.0, 8.0}) {
      for (int i = 0; i < static_cast<int>(side / kStep); ++i) {
        path.push_back(pose);
        pose = pose * Pose2(kStep, 0.0, 0.0);
      }
      for (int i = 0; i < 3; ++i) {
        path.push_back(pose);
        pose = pose * Pose2(0.0, 0.0, M_PI / 6.0);
      }
    }
  }
  return path;
}

// noise_scale scales the drift (0: an exact front end); nodes slip_first..slip_last are put
// `slip` metres ahead along their heading after the drift, the nodes after them left in place.
SimulatedGraph Simulate(std::uint64_t seed, double noise_scale = 1.0, int slip_first = 0,
                        int slip_last = -1, double slip = 0.0) {
  SimulatedGraph g;
  g.truth = RectangleLaps(2);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  const double kTranslationNoise = 0.01 * noise_scale;  // m per step
  const double kHeadingNoise = 0.002 * noise_scale;     // rad per step
  const double kHeadingBias = 0.001 * noise_scale;      // rad per step
  g.local.push_back(g.truth.front());
  for (std::size_t i = 1; i < g.truth.size(); ++i) {
    const Pose2 motion = RelativePose(g.truth[i - 1], g.truth[i]);
    const Pose2 noisy(motion.x + kTranslationNoise * n(rng), motion.y + kTranslationNoise * n(rng),
                      motion.theta + kHeadingBias + kHeadingNoise * n(rng));
    g.local.push_back(g.local.back() * noisy);
  }
  for (int i = slip_first; i <= slip_last; ++i) g.local[i] = g.local[i] * Pose2(slip, 0.0, 0.0);
  const int laps_nodes = static_cast<int>(g.truth.size()) / 2;
  for (std::size_t i = 0; i < g.truth.size(); ++i) {
    g.lap.push_back(static_cast<int>(i) < laps_nodes ? 0 : 1);
    if (i % kNodesPerSubmap == 0) {
      g.submap_local.push_back(Pose2(g.local[i].x, g.local[i].y, 0.0));
      g.submap_truth.push_back(g.truth[i] * RelativePose(g.local[i], g.submap_local.back()));
    }
    const int newest = static_cast<int>(g.submap_local.size()) - 1;
    for (int s = std::max(0, newest - 1); s <= newest; ++s) {
      g.local_constraints.push_back(
          {s, static_cast<int>(i), RelativePose(g.submap_local[s], g.local[i]),
           ConstraintTag::kLocal, 0.0});
    }
  }
  return g;
}

// Loop constraints for every third node of the second lap against the first lap's submap whose
// origin is nearest, measured from the truth with 1 cm and 2 mrad of noise.
std::vector<Constraint> LoopConstraints(const SimulatedGraph& g, std::mt19937_64* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Constraint> loops;
  for (std::size_t i = 0; i < g.truth.size(); i += 3) {
    if (g.lap[i] == 0) continue;
    int nearest = 0;
    double best = 1e9;
    for (std::size_t s = 0; s < g.submap_truth.size(); ++s) {
      if (g.lap[s * kNodesPerSubmap] != 0) continue;
      const double d = (g.submap_truth[s].translation() - g.truth[i].translation()).norm();
      if (d < best) best = d, nearest = static_cast<int>(s);
    }
    Pose2 relative = RelativePose(g.submap_truth[nearest], g.truth[i]);
    relative = Pose2(relative.x + 0.01 * n(*rng), relative.y + 0.01 * n(*rng),
                     relative.theta + 0.002 * n(*rng));
    loops.push_back({nearest, static_cast<int>(i), relative, ConstraintTag::kLoop, 0.8});
  }
  return loops;
}

PoseGraph Build(const SimulatedGraph& g, const std::vector<Constraint>& loops,
                const PoseGraphOptions& options) {
  PoseGraph graph(options);
  for (const Pose2& s : g.submap_local) graph.AddSubmap(s);
  for (const Pose2& n : g.local) graph.AddNode(n);
  for (const Constraint& c : g.local_constraints) graph.AddConstraint(c);
  for (std::size_t i = 1; i < g.local.size(); ++i) {
    graph.AddConsecutiveConstraint({static_cast<int>(i) - 1, static_cast<int>(i),
                                    RelativePose(g.local[i - 1], g.local[i])});
  }
  for (const Constraint& c : loops) graph.AddConstraint(c);
  return graph;
}

double RmsError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    sum += (estimate[i].translation() - truth[i].translation()).squaredNorm();
  }
  return std::sqrt(sum / truth.size());
}

double MaxError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, (estimate[i].translation() - truth[i].translation()).norm());
  }
  return worst;
}

TEST(PoseGraphTest, LoopConstraintsRemoveTheDriftAgainstTheTruth) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const SimulatedGraph g = Simulate(seed);
    std::mt19937_64 rng(seed + 100);
    PoseGraph graph = Build(g, LoopConstraints(g, &rng), PoseGraphOptions());
    const double before = RmsError(graph.node_poses(), g.truth);
    const OptimizationSummary summary = graph.Optimize();
    ASSERT_TRUE(summary.solved) << summary.message;
    const double after = RmsError(graph.node_poses(), g.truth);
    // Measured: RMS 0.57-0.86 m before, 0.053-0.068 m after (worst node 0.12-0.14 m; 0.066-0.075
    // and 0.14-0.18 m with the consecutive constraints ten times the loop ones): what is left is
    // the first lap's own drift between its closures, which no loop constraint sees.
    EXPECT_GT(before, 0.5) << "seed " << seed;
    EXPECT_LT(after, 0.08) << "seed " << seed << ", before " << before;
    EXPECT_LT(after, before / 7.0) << "seed " << seed;
    EXPECT_LT(MaxError(graph.node_poses(), g.truth), 0.17) << "seed " << seed;
    // The first submap is the fixed gauge.
    EXPECT_DOUBLE_EQ(graph.submap_poses().front().x, g.submap_local.front().x);
  }
}

// A loop constraint that claims a node of the far side of the loop lies 4 m and 1 rad away from
// where it is: the Huber loss bounds its pull, so the many right ones outvote it; without the
// loss (least squares) it bends the map.
TEST(PoseGraphTest, HuberLossRejectsAWrongLoopConstraint) {
  const SimulatedGraph g = Simulate(4);
  std::mt19937_64 rng(5);
  std::vector<Constraint> loops = LoopConstraints(g, &rng);
  Constraint wrong = loops[loops.size() / 2];
  wrong.relative = wrong.relative * Pose2(4.0, -2.0, 1.0);
  loops.push_back(wrong);

  PoseGraph robust = Build(g, loops, PoseGraphOptions());
  ASSERT_TRUE(robust.Optimize().solved);
  PoseGraphOptions least_squares_options;
  least_squares_options.huber_scale = 0.0;
  PoseGraph least_squares = Build(g, loops, least_squares_options);
  ASSERT_TRUE(least_squares.Optimize().solved);
  loops.pop_back();
  PoseGraph clean = Build(g, loops, PoseGraphOptions());
  ASSERT_TRUE(clean.Optimize().solved);

  // Measured: the robust solution within 1.2 mm of the one without the wrong constraint (RMS
  // against the truth 0.147 m for both); least squares 0.66 m off it.
  EXPECT_LT(MaxError(robust.node_poses(), clean.node_poses()), 0.003);
  EXPECT_LT(RmsError(robust.node_poses(), g.truth), 1.02 * RmsError(clean.node_poses(), g.truth));
  EXPECT_GT(MaxError(least_squares.node_poses(), clean.node_poses()), 0.5);
}

// The first lap's nodes kSlipFirst..kSlipLast (on its first side) slipped: the front end,
// exact otherwise, inserted them 0.25 m ahead of where they were, as when the robot spins
// where a corridor leaves the matches free along it, and the nodes after them are back in
// place. The first and last of them have loop constraints, measured from the truth, on two of
// the second lap's submaps, and so do a node three before the slip and one three after it
// (on the first of those submaps; the one after as offset as the slip when `regional`); the
// second lap has its own (LoopConstraints).
constexpr int kSlipFirst = 12;
constexpr int kSlipLast = 15;
constexpr double kSlip = 0.25;

PoseGraph SlippedGraph(const SimulatedGraph& g, int loop_submap_a, int loop_submap_b,
                       double b_error, const PoseGraphOptions& options, bool regional = false) {
  std::mt19937_64 rng(7);
  std::vector<Constraint> loops = LoopConstraints(g, &rng);
  for (const int node : {kSlipFirst - 3, kSlipLast + 3}) {
    const double offset = regional && node > kSlipLast ? -kSlip : 0.0;
    loops.push_back({loop_submap_a, node,
                     RelativePose(g.submap_truth[loop_submap_a], g.truth[node]) *
                         Pose2(offset, 0.0, 0.0),
                     ConstraintTag::kLoop, 0.8});
  }
  for (const int node : {kSlipFirst, kSlipLast}) {
    loops.push_back({loop_submap_a, node,
                     RelativePose(g.submap_truth[loop_submap_a], g.truth[node]),
                     ConstraintTag::kLoop, 0.8});
    loops.push_back({loop_submap_b, node,
                     RelativePose(g.submap_truth[loop_submap_b], g.truth[node]) *
                         Pose2(b_error, 0.0, 0.0),
                     ConstraintTag::kLoop, 0.8});
  }
  return Build(g, loops, options);
}

double SlipLeft(const PoseGraph& graph, const SimulatedGraph& g) {
  double worst = 0.0;
  for (int i = kSlipFirst; i <= kSlipLast; ++i) {
    worst =
        std::max(worst, (graph.node_poses()[i].translation() - g.truth[i].translation()).norm());
  }
  return worst;
}

double ErrorElsewhere(const PoseGraph& graph, const SimulatedGraph& g) {
  double worst = 0.0;
  for (int i = 0; i < static_cast<int>(g.truth.size()); ++i) {
    if (i >= kSlipFirst && i <= kSlipLast) continue;
    worst =
        std::max(worst, (graph.node_poses()[i].translation() - g.truth[i].translation()).norm());
  }
  return worst;
}

int SecondLapSubmapAt(const SimulatedGraph& g, int first_lap_node) {
  const int lap_nodes = static_cast<int>(g.truth.size()) / 2;
  return (lap_nodes + first_lap_node) / kNodesPerSubmap;
}

// Loop constraints on two submaps that share no node agree on where the slipped nodes were: the
// graph puts them back. Without the check the consecutive constraints hold them where the front
// end put them, whatever the loop constraints say.
TEST(PoseGraphTest, TwoIndependentLoopConstraintsPutASlippedNodeBack) {
  const SimulatedGraph g = Simulate(6, 0.0, kSlipFirst, kSlipLast, kSlip);
  const int a = SecondLapSubmapAt(g, kSlipFirst), b = a + 2;  // a + 1 shares a's newer half
  PoseGraph checked = SlippedGraph(g, a, b, 0.0, PoseGraphOptions());
  const OptimizationSummary summary = checked.Optimize();
  ASSERT_TRUE(summary.solved) << summary.message;
  EXPECT_EQ(summary.slipped_nodes, 2);
  PoseGraphOptions unchecked_options;
  unchecked_options.slip_distance = 0.0;
  PoseGraph unchecked = SlippedGraph(g, a, b, 0.0, unchecked_options);
  ASSERT_TRUE(unchecked.Optimize().solved);
  // Measured: the slipped nodes 0.070 m from the truth (0.236 m without the check). The second
  // lap's two submaps took the rest: the first solution had already pulled them towards the
  // slipped nodes, which their loop constraints now place to within a centimetre. The worst
  // node elsewhere 0.025 m off (0.022 m without the check).
  EXPECT_LT(SlipLeft(checked, g), 0.077);
  EXPECT_GT(SlipLeft(unchecked, g), 0.2);
  EXPECT_LT(ErrorElsewhere(checked, g), 0.028);
  EXPECT_LT(ErrorElsewhere(unchecked, g), 0.024);
  // Found slipped, a node stays so, even when later evidence, read alone, would no longer find
  // it: here a loop constraint on the node after the slip that places it as far off as the
  // slip (without the node kept, the rule's bound fails and the next optimisation puts the
  // slipped nodes back where the front end had them: measured 0.228 m).
  const double left = SlipLeft(checked, g);
  checked.AddConstraint({a, kSlipLast + 1,
                         RelativePose(g.submap_truth[a], g.truth[kSlipLast + 1]) *
                             Pose2(-kSlip, 0.0, 0.0),
                         ConstraintTag::kLoop, 0.8});
  const OptimizationSummary next = checked.Optimize();
  ASSERT_TRUE(next.solved) << next.message;
  EXPECT_EQ(next.slipped_nodes, 2);
  EXPECT_NEAR(SlipLeft(checked, g), left, 0.002);
}

// The same loop constraints but on two submaps that share nodes (and so would share a front
// end's error), on two that do not but disagree by 0.3 m, or with the node after the slip as
// far off the second lap's submap as the slipped ones (a stretch offset from another pass, not
// a slip of its own): no evidence of a slip, and the solution is the one without the check,
// to the bit.
TEST(PoseGraphTest, SharedOrDisagreeingLoopConstraintsAreNoSlip) {
  const SimulatedGraph g = Simulate(6, 0.0, kSlipFirst, kSlipLast, kSlip);
  const int a = SecondLapSubmapAt(g, kSlipFirst);
  PoseGraphOptions unchecked_options;
  unchecked_options.slip_distance = 0.0;
  const std::tuple<int, double, bool> cases[] = {{a + 1, 0.0, false}, {a + 2, 0.3, false},
                                                 {a + 2, 0.0, true}};
  for (const auto& [b, error, regional] : cases) {
    PoseGraph checked = SlippedGraph(g, a, b, error, PoseGraphOptions(), regional);
    const OptimizationSummary summary = checked.Optimize();
    ASSERT_TRUE(summary.solved) << summary.message;
    EXPECT_EQ(summary.slipped_nodes, 0) << "submap " << b << (regional ? ", regional" : "");
    PoseGraph unchecked = SlippedGraph(g, a, b, error, unchecked_options, regional);
    ASSERT_TRUE(unchecked.Optimize().solved);
    for (std::size_t i = 0; i < g.truth.size(); ++i) {
      ASSERT_EQ(checked.node_poses()[i].x, unchecked.node_poses()[i].x) << "node " << i;
    }
    // Measured: the slipped nodes stay 0.236 m (shared), 0.259 m (disagreeing) and 0.222 m
    // (regional) off.
    EXPECT_GT(SlipLeft(checked, g), 0.2) << "submap " << b;
  }
}

TEST(PoseGraphTest, ResidualWrapsTheAngleAndWeighs) {
  const Constraint c{0, 0, Pose2(1.0, 0.0, M_PI - 0.1), ConstraintTag::kLoop, 0.0};
  // Submap at the origin turned by π/2; node 1 m along its x axis, turned by -π + 0.1 more: the
  // angle error is 0.2 rad across the ±π seam, not 2π - 0.2.
  const Pose2 submap(0.0, 0.0, M_PI / 2);
  const Pose2 node(0.0, 1.0 + 0.05, NormalizeAngle(M_PI / 2 - M_PI + 0.1));
  const Eigen::Vector3d r = ConstraintResidual(c, submap, node, 10.0, 100.0);
  EXPECT_NEAR(r.x(), 10.0 * 0.05, 1e-12);
  EXPECT_NEAR(r.y(), 0.0, 1e-12);
  EXPECT_NEAR(r.z(), 100.0 * 0.2, 1e-9);
}

TEST(PoseGraphTest, ConstraintsNeedBothEndsAndBadOptionsAreNamed) {
  PoseGraph graph{PoseGraphOptions()};
  graph.AddSubmap(Pose2());
  EXPECT_THROW(graph.AddConstraint({0, 0, Pose2(), ConstraintTag::kLocal, 0.0}), std::out_of_range);
  EXPECT_TRUE(graph.Optimize().solved);  // nothing to do
  PoseGraphOptions bad;
  bad.loop_translation_weight = 0.0;
  bad.huber_scale = -1.0;
  bad.max_num_iterations = 0;
  bad.slip_distance = std::nan("");
  bad.slip_angle = -1.0;
  const std::vector<std::string> errors = bad.Validate();
  ASSERT_EQ(errors.size(), 5u);
  EXPECT_NE(errors[0].find("loop_closure_translation_weight"), std::string::npos);
}

}  // namespace
}  // namespace mapping
}  // namespace hex_slam
