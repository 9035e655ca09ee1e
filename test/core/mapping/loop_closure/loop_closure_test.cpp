#include "hex_slam/mapping/loop_closure/loop_closure.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "../../test_maps.h"
#include "../submap_grid.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/sim/building_loop.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/sim/segment_world.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {
namespace {

LoopClosureOptions SmallSubmaps() {
  LoopClosureOptions options;
  options.submaps.num_scans = 12;
  options.optimize_every_n_nodes = 12;
  options.constraints.sampling_ratio = 0.2;
  options.constraints.search_level = 1;
  return options;
}

// Twice round the test room's loop, every 10th scan inserted, at poses that drift from the
// truth (a heading bias of 1 mrad per insertion, as a drifting front end would give): the back
// end's loop constraints must pull the second lap back onto the first.
struct DriftingDrive {
  std::vector<Pose2> truth;
  std::vector<Pose2> local;
  std::vector<std::vector<Eigen::Vector2d>> points;
};

// d->local from d->truth: the truth's motion between nodes, turned by `bias` (rad) at each.
void DriftHeading(double bias, DriftingDrive* d) {
  d->local.assign(1, d->truth.front());
  for (std::size_t i = 1; i < d->truth.size(); ++i) {
    d->local.push_back(d->local.back() * RelativePose(d->truth[i - 1], d->truth[i]) *
                       Pose2(0.0, 0.0, bias));
  }
}

DriftingDrive Drive() {
  const sim::RoomDrive room = sim::MakeRoomDrive(360);
  std::mt19937_64 rng(12);
  DriftingDrive d;
  for (int lap = 0; lap < 2; ++lap) {
    for (std::size_t i = 0; i < room.truth.size(); i += 10) {
      d.truth.push_back(room.truth[i]);
      d.points.push_back(testing_util::ScanPoints(room.world, room.truth[i], room.lidar, &rng));
    }
  }
  DriftHeading(1e-3, &d);
  return d;
}

double RmsError(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    sum += (estimate[i].translation() - truth[i].translation()).squaredNorm();
  }
  return std::sqrt(sum / truth.size());
}

template <class Lattice>
std::shared_ptr<const PoseGraphSolution> RunBackEnd(const DriftingDrive& d,
                                                    std::atomic<int>* published = nullptr,
                                                    int max_queued_submaps = 0,
                                                    LoopClosureStats* stats_out = nullptr,
                                                    int max_queued_submap_pyramids = -1) {
  auto board = std::make_shared<LatestSolution>();
  if (published) board->SetListener([published](std::uint64_t) { ++*published; });
  LoopClosureOptions options = SmallSubmaps();
  options.max_queued_submaps = max_queued_submaps;
  options.max_queued_submap_pyramids = max_queued_submap_pyramids;
  LoopClosure<Lattice> back_end(options, ScanMatcherOptions(), testing_util::SubmapGrid(3), board);
  for (std::size_t i = 0; i < d.local.size(); ++i) {
    EXPECT_EQ(back_end.InsertScan(0.1 * i, d.local[i], Eigen::Vector2d::Zero(), d.points[i]),
              static_cast<int>(i));
  }
  back_end.FinishTrajectory();
  const LoopClosureStats stats = back_end.stats();
  EXPECT_TRUE(stats.first_error.empty()) << stats.first_error;
  EXPECT_EQ(stats.nodes, static_cast<int>(d.local.size()));
  EXPECT_EQ(stats.finished_submaps, stats.submaps);
  EXPECT_GT(stats.loop_constraints, 10);
  EXPECT_EQ(stats.queued, 0u);
  if (stats_out) *stats_out = stats;
  return board->Get();
}

template <class T>
class LoopClosureTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(LoopClosureTest, Lattices);

TYPED_TEST(LoopClosureTest, PullsADriftingTrajectoryBackOntoTheTruth) {
  const DriftingDrive d = Drive();
  std::atomic<int> published{0};
  const auto solution = RunBackEnd<TypeParam>(d, &published);
  ASSERT_EQ(solution->node_poses.size(), d.truth.size());
  EXPECT_EQ(static_cast<int>(solution->version), published.load());
  EXPECT_GE(solution->version, 1u);
  const double before = RmsError(d.local, d.truth);
  const double after = RmsError(solution->node_poses, d.truth);
  // Measured: 0.39 m before; 0.023 (hex) and 0.022 m (square) after.
  EXPECT_GT(before, 0.35);
  EXPECT_LT(after, 0.03) << "before " << before;
  // The newest node's pose is the correction applied to its front-end pose.
  const Pose2 last = solution->correction * d.local.back();
  EXPECT_NEAR(last.x, solution->node_poses.back().x, 1e-9);
  EXPECT_NEAR(last.y, solution->node_poses.back().y, 1e-9);
}

// A worker that falls behind the node keeps no finished submap's grids in its queue beyond
// max_queued_submap_pyramids: with none kept, every finished submap is queued as its id alone
// and drawn again from its nodes, and the drift is still pulled back onto the truth.
TEST(LoopClosureTest, SubmapsQueuedWithoutTheirGridsAreDrawnAgainAndStillCloseTheLoop) {
  const DriftingDrive d = Drive();
  LoopClosureStats stats;
  const auto solution = RunBackEnd<HexLattice>(d, nullptr, 0, &stats, 0);
  ASSERT_EQ(solution->node_poses.size(), d.truth.size());
  EXPECT_EQ(stats.pyramids_not_queued, stats.finished_submaps);
  EXPECT_GE(stats.submaps_redrawn, stats.finished_submaps);
  // Measured: 0.0229 m, all 18 submaps drawn again; 0.023 m with their own grids
  // (PullsADriftingTrajectoryBackOntoTheTruth).
  EXPECT_LT(RmsError(solution->node_poses, d.truth), 0.03);
  LoopClosureStats kept;
  RunBackEnd<HexLattice>(d, nullptr, 0, &kept, -1);
  EXPECT_EQ(kept.pyramids_not_queued, 0);
}

// A finished trajectory gives the worker's cache back (an offline run draws its map and writes
// its files next): the first lap's submaps, all held while it ran, are drawn again from their
// nodes when a second lap comes after FinishTrajectory, and that lap still closes on them.
TEST(LoopClosureTest, FinishingATrajectoryEmptiesTheCacheAndLaterNodesStillCloseLoops) {
  const DriftingDrive d = Drive();
  const std::size_t lap = d.local.size() / 2;
  auto board = std::make_shared<LatestSolution>();
  LoopClosure<HexLattice> back_end(SmallSubmaps(), ScanMatcherOptions(),
                                   testing_util::SubmapGrid(3), board);
  for (std::size_t i = 0; i < lap; ++i) back_end.InsertScan(0.1 * i, d.local[i], {0, 0}, d.points[i]);
  back_end.FinishTrajectory();
  const LoopClosureStats first = back_end.stats();
  EXPECT_EQ(first.submaps_redrawn, 0);  // the budget (256 MB) held every submap of the lap
  EXPECT_GT(first.cached_submap_bytes, 0u);
  for (std::size_t i = lap; i < d.local.size(); ++i) {
    back_end.InsertScan(0.1 * i, d.local[i], {0, 0}, d.points[i]);
  }
  back_end.FinishTrajectory();
  const LoopClosureStats second = back_end.stats();
  EXPECT_TRUE(second.first_error.empty()) << second.first_error;
  EXPECT_GT(second.submaps_redrawn, 0);
  EXPECT_GT(second.loop_constraints, first.loop_constraints + 10);
  // As PullsADriftingTrajectoryBackOntoTheTruth, whose single run measures 0.023 m.
  const double after = RmsError(board->Get()->node_poses, d.truth);
  std::cout << "after a finished first lap: RMS " << after << " m, " << second.submaps_redrawn
            << " submaps redrawn\n";
  EXPECT_LT(after, 0.03);
}

// Every decision depends on the order of the jobs, not on when the worker got to them.
TEST(LoopClosureTest, TheSameScansGiveTheSameSolution) {
  const DriftingDrive d = Drive();
  const auto a = RunBackEnd<HexLattice>(d);
  const auto b = RunBackEnd<HexLattice>(d);
  ASSERT_EQ(a->node_poses.size(), b->node_poses.size());
  for (std::size_t i = 0; i < a->node_poses.size(); ++i) {
    EXPECT_EQ(a->node_poses[i].x, b->node_poses[i].x);
    EXPECT_EQ(a->node_poses[i].theta, b->node_poses[i].theta);
  }
  EXPECT_EQ(a->loop_constraints, b->loop_constraints);
}

// An offline run's scan path waits for the worker to take the queued finished submaps: that
// bounds the memory they hold and changes nothing the worker decides.
TEST(LoopClosureTest, WaitingForTheWorkerChangesNoResult) {
  const DriftingDrive d = Drive();
  const auto free_running = RunBackEnd<HexLattice>(d);
  const auto waiting = RunBackEnd<HexLattice>(d, nullptr, 1);
  ASSERT_EQ(free_running->node_poses.size(), waiting->node_poses.size());
  for (std::size_t i = 0; i < waiting->node_poses.size(); ++i) {
    EXPECT_EQ(free_running->node_poses[i].x, waiting->node_poses[i].x);
    EXPECT_EQ(free_running->node_poses[i].theta, waiting->node_poses[i].theta);
  }
  EXPECT_EQ(free_running->loop_constraints, waiting->loop_constraints);
}

// The fraction of the truth's endpoints (every 25th scan of a lap) that land on occupied cells
// of the map drawn from the nodes at the solution's poses.
double WallAgreement(const PoseGraphSolution& solution) {
  MapPyramid<HexLattice> drawn(0.05, 1, testing_util::SubmapGrid(3).model, GridGrowthPolicy(),
                               Eigen::AlignedBox2d(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)));
  DrawGlobalMap(solution.nodes, solution, &drawn);
  const sim::RoomDrive room = sim::MakeRoomDrive(360);
  std::mt19937_64 rng(13);
  int on_wall = 0, total = 0;
  for (std::size_t i = 0; i < room.truth.size(); i += 25) {
    for (const Eigen::Vector2d& p :
         testing_util::ScanPoints(room.world, room.truth[i], room.lidar, &rng)) {
      ++total;
      const GridMap<HexLattice>& map = drawn.level(0);
      on_wall += map.Probability(map.lattice().CellOf(room.truth[i] * p)) > 0.5 ? 1 : 0;
    }
  }
  return static_cast<double>(on_wall) / total;
}

// The global map drawn at the optimised poses puts the walls where the truth's would, and where
// the drifting front end's would not.
TEST(LoopClosureTest, TheGlobalMapIsDrawnAtTheOptimisedPoses) {
  const DriftingDrive d = Drive();
  const auto optimised = RunBackEnd<HexLattice>(d);
  PoseGraphSolution truth = *optimised, drifting = *optimised;
  truth.node_poses = d.truth;
  drifting.node_poses = d.local;
  const double at_truth = WallAgreement(truth);
  const double at_optimised = WallAgreement(*optimised);
  const double at_drifting = WallAgreement(drifting);
  // Measured: 0.973 at the truth, 0.876 at the optimised poses (2.3 cm RMS off it: the heading
  // drift warps the submaps themselves, which the graph takes for rigid), 0.565 drifting.
  EXPECT_GT(at_truth, 0.95);
  EXPECT_GT(at_optimised, 0.85);
  EXPECT_LT(at_drifting, 0.6);
}

// The whole drawing's storage is taken at once (grown node by node, a long corridor's map was
// copied into larger storage again and again), and every cell is what drawing the nodes one by
// one into growing storage gives.
TEST(LoopClosureTest, TheGlobalMapTakesItsStorageOnceAndHoldsWhatEachNodeDraws) {
  PoseGraphSolution solution;  // a 40 m corridor, a node every 2 m seeing 3 m of both walls
  for (int i = 0; i <= 20; ++i) {
    auto node = std::make_shared<TrajectoryNode>();
    node->id = i;
    node->local_pose = Pose2(2.0 * i, 0.0, 0.1 * i);
    for (double x = -1.5; x <= 1.5; x += 0.02) {
      for (double wall : {-1.0, 1.0}) {
        node->points.push_back(Pose2(0.0, 0.0, -0.1 * i) * Eigen::Vector2d(x, wall));
      }
    }
    solution.nodes.push_back(node);
    solution.node_poses.push_back(node->local_pose);
  }
  const Eigen::AlignedBox2d small(Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(0.5, 0.5));
  const OccupancyModel model = testing_util::SubmapGrid(3).model;
  MapPyramid<HexLattice> drawn(0.05, 3, model, GridGrowthPolicy(), small);
  MapPyramid<HexLattice> grown(0.05, 3, model, GridGrowthPolicy(), small);
  DrawGlobalMap(solution.nodes, solution, &drawn);
  for (const auto& node : solution.nodes) {  // one scan at a time, storage growing as needed
    const Pose2 pose = solution.node_poses[node->id];
    std::vector<Eigen::Vector2d> points;
    for (const Eigen::Vector2d& p : node->points) points.push_back(pose * p);
    grown.InsertScan(pose.translation(), points);
  }
  for (int k = 0; k < 3; ++k) {
    const GridMap<HexLattice>& once = drawn.level(k);
    const GridMap<HexLattice>& stepwise = grown.level(k);
    EXPECT_EQ(once.growth_count(), 1) << "level " << k;
    EXPECT_GT(stepwise.growth_count(), 2) << "level " << k;
    int known = 0, differing = 0;
    for (const GridRect& rect : {once.rect(), stepwise.rect()}) {
      for (int row = rect.min.row; row < rect.min.row + rect.height; ++row) {
        for (int col = rect.min.col; col < rect.min.col + rect.width; ++col) {
          const GridIndex index{col, row};
          known += once.IsKnownAt(index) ? 1 : 0;
          differing += once.ProbabilityAt(index) != stepwise.ProbabilityAt(index) ? 1 : 0;
        }
      }
    }
    EXPECT_GT(known, 0);
    EXPECT_EQ(differing, 0) << "level " << k;
  }
}

TEST(PoseGraphSolutionTest, ScansAfterANodeMoveWithIt) {
  PoseGraphSolution s;
  auto node = std::make_shared<TrajectoryNode>();
  node->local_pose = Pose2(1.0, 0.0, 0.0);
  s.nodes.push_back(node);
  s.node_poses.push_back(Pose2(5.0, 5.0, M_PI / 2));
  s.correction = Pose2(-1.0, 0.0, 0.0);
  const Pose2 after = s.ToGlobal(Pose2(2.0, 0.0, 0.0), 0);  // 1 m ahead of the node
  EXPECT_NEAR(after.x, 5.0, 1e-12);
  EXPECT_NEAR(after.y, 6.0, 1e-12);
  EXPECT_NEAR(after.theta, M_PI / 2, 1e-12);
  const Pose2 unknown = s.ToGlobal(Pose2(2.0, 0.0, 0.0), 3);  // a node it does not know
  EXPECT_NEAR(unknown.x, 1.0, 1e-12);
}

TEST(LatestSolutionTest, PublishingCountsVersionsAndTellsTheListener) {
  LatestSolution board;
  EXPECT_EQ(board.version(), 0u);
  EXPECT_EQ(board.Get()->version, 0u);
  std::uint64_t heard = 0;
  board.SetListener([&heard](std::uint64_t v) { heard = v; });
  board.Publish(PoseGraphSolution());
  board.Publish(PoseGraphSolution());
  EXPECT_EQ(board.version(), 2u);
  EXPECT_EQ(board.Get()->version, 2u);
  EXPECT_EQ(heard, 2u);
}

// A straight drive once through a hall, so no loop exists. Boxes stand along the way at random,
// three a metre, and no wall is within the 4 m lidar's reach: what a scan sees says where the
// robot is. One node's
// scan was taken 16 m back (as a scan that happens to look like another place would be): a
// global search puts that node back there, but the nodes after it see what really surrounds
// them. The front end's poses are the truth, the oracle.
struct CorridorDrive {
  std::vector<Pose2> truth;
  std::vector<std::vector<Eigen::Vector2d>> points;
  std::size_t misplaced = 0;  // the node whose scan was taken elsewhere
};

// `metres` of corridor from x = `start` along the x axis: boxes on either side of y = 0 at
// places drawn from `seed` (the same seed, the same stretch).
void AddBoxCorridor(double start, int metres, unsigned seed, sim::SegmentWorld* world) {
  constexpr int kBoxesPerMetre = 3;
  constexpr double kBox = 0.3, kNearest = 0.6, kFarthest = 3.0;
  std::mt19937_64 pattern(seed);
  std::uniform_real_distribution<double> along(0.0, 1.0 - kBox), across(kNearest, kFarthest);
  for (int m = 0; m < metres; ++m) {
    for (int b = 0; b < kBoxesPerMetre; ++b) {
      const double side = b % 2 == 0 ? 1.0 : -1.0;
      const Eigen::Vector2d corner(start + m + along(pattern),
                                   side * across(pattern) - 0.5 * kBox);
      world->AddRectangle(corner, corner + Eigen::Vector2d(kBox, kBox));
    }
  }
}

constexpr double kCorridorLidarRange = 4.0;  // m
constexpr double kCorridorStep = 0.2;        // m between nodes

CorridorDrive StraightCorridorWithAMisplacedScan() {
  constexpr int kMetres = 32;
  constexpr double kMisplacedBy = 16.0;
  sim::SegmentWorld world;
  AddBoxCorridor(0.0, kMetres, 3, &world);
  sim::LidarModel lidar;
  lidar.range_max = kCorridorLidarRange;
  std::mt19937_64 rng(5);
  CorridorDrive d;
  for (double x = 1.0; x < kMetres - kCorridorLidarRange; x += kCorridorStep) {
    d.truth.emplace_back(x, 0.0, 0.0);
    d.points.push_back(testing_util::ScanPoints(world, d.truth.back(), lidar, &rng));
  }
  d.misplaced = static_cast<std::size_t>((22.0 - 1.0) / kCorridorStep);
  d.points[d.misplaced] = testing_util::ScanPoints(
      world, Pose2(d.truth[d.misplaced].x - kMisplacedBy, 0.0, 0.0), lidar, &rng);
  return d;
}

// How many of the solution's loop constraints put their node more than `tolerance` (m) from
// where the truth has it on their submap.
int WrongLoopConstraints(const PoseGraphSolution& solution, const std::vector<Pose2>& truth,
                         double tolerance) {
  int wrong = 0;
  for (const Constraint& c : solution.constraints) {
    if (c.tag != ConstraintTag::kLoop) continue;
    const Pose2 expected = RelativePose(solution.submap_local_poses[c.submap], truth[c.node]);
    if ((expected.translation() - c.relative.translation()).norm() > tolerance) ++wrong;
  }
  return wrong;
}

LoopClosureOptions GlobalSearchesOnlyForEveryNode() {
  LoopClosureOptions options = SmallSubmaps();
  options.submaps.num_scans = 20;
  options.constraints.sampling_ratio = 0.0;
  options.constraints.global_constraint_search_after_n_seconds = 0.0;
  options.constraints.global_sampling_ratio = 1.0;
  return options;
}

// A global match takes a place only once a node further on is found where it says.
TEST(LoopClosureTest, AGlobalMatchNoLaterNodeConfirmsNeverReachesTheGraph) {
  const CorridorDrive d = StraightCorridorWithAMisplacedScan();
  for (const bool confirm : {true, false}) {
    SCOPED_TRACE(confirm ? "confirmed" : "taken at once");
    LoopClosureOptions options = GlobalSearchesOnlyForEveryNode();
    if (!confirm) options.constraints.global_confirm_max_distance = 0.0;
    auto board = std::make_shared<LatestSolution>();
    LoopClosure<HexLattice> back_end(options, ScanMatcherOptions(), testing_util::SubmapGrid(3),
                                     board);
    for (std::size_t i = 0; i < d.truth.size(); ++i) {
      back_end.InsertScan(0.1 * i, d.truth[i], Eigen::Vector2d::Zero(), d.points[i]);
    }
    back_end.FinishTrajectory();
    const LoopClosureStats stats = back_end.stats();
    const std::shared_ptr<const PoseGraphSolution> solution = board->Get();
    ASSERT_TRUE(solution);
    const int wrong = WrongLoopConstraints(*solution, d.truth, 0.5);
    std::cout << (confirm ? "confirmed: " : "at once: ") << stats.search.global_found
              << " global matches, " << stats.global_confirmed << " confirmed, "
              << stats.global_unconfirmed << " dropped; " << solution->loop_constraints
              << " loop constraints, " << wrong << " wrong\n";
    if (confirm) {
      EXPECT_EQ(wrong, 0);
      // Measured: 21 of 29 matches confirmed (those on the submaps a node overlaps), no wrong one.
      EXPECT_GT(stats.global_confirmed, 10);
    } else {
      // Measured: 41 matches, the misplaced scan's 2 among them.
      EXPECT_GT(wrong, 0);
    }
  }
}

// Three copies of one 12 m stretch of corridor along x, each after 8 m of corridor of its own,
// driven at known poses. Global searches are due only once the scans see nothing but the third
// copy; then every node is searched on every submap and fits the first copy and the second,
// 20 m apart. One of the two places is wrong and the node alone cannot tell which: when the
// other copy scores within ambiguity_ratio of the best (on a submap where the search found
// it, or on one searched again down to that score), neither may reach the graph. Oracle: the
// truth.
TEST(LoopClosureTest, GlobalMatchesThatPlaceANodeInTwoPlacesAreRefused) {
  constexpr int kCopyMetres = 12, kGapMetres = 8, kCopies = 3;
  constexpr unsigned kCopySeed = 3, kFirstGapSeed = 11;
  constexpr double kQuiet = 100.0;  // s before global searches are due
  sim::SegmentWorld world;
  for (int c = 0; c < kCopies; ++c) {
    const double start = c * (kGapMetres + kCopyMetres);
    AddBoxCorridor(start, kGapMetres, kFirstGapSeed + c, &world);
    AddBoxCorridor(start + kGapMetres, kCopyMetres, kCopySeed, &world);
  }
  sim::LidarModel lidar;
  lidar.range_max = kCorridorLidarRange;
  LoopClosureOptions options = GlobalSearchesOnlyForEveryNode();
  options.constraints.global_constraint_search_after_n_seconds = kQuiet;
  auto board = std::make_shared<LatestSolution>();
  LoopClosure<HexLattice> back_end(options, ScanMatcherOptions(), testing_util::SubmapGrid(3),
                                   board);
  std::mt19937_64 rng(7);
  std::vector<Pose2> truth;
  // Searched from where a node's scan sees the third copy alone.
  const double searched = (kCopies - 1) * (kGapMetres + kCopyMetres) + kGapMetres +
                          kCorridorLidarRange;
  const double end = kCopies * (kGapMetres + kCopyMetres) - kCorridorLidarRange;
  for (double x = 1.0; x < end; x += kCorridorStep) {
    truth.emplace_back(x, 0.0, 0.0);
    const double stamp = (x < searched ? 0.0 : 2.0 * kQuiet) + 0.1 * truth.size();
    back_end.InsertScan(stamp, truth.back(), Eigen::Vector2d::Zero(),
                        testing_util::ScanPoints(world, truth.back(), lidar, &rng));
  }
  back_end.FinishTrajectory();
  const LoopClosureStats stats = back_end.stats();
  const std::shared_ptr<const PoseGraphSolution> solution = board->Get();
  ASSERT_TRUE(solution);
  const int wrong = WrongLoopConstraints(*solution, truth, 0.5);
  std::cout << stats.search.global_searches << " global searches found "
            << stats.search.global_found << ", " << stats.global_rivals
            << " refused as rivals, " << stats.global_confirmed << " confirmed; "
            << solution->loop_constraints << " loop constraints, " << wrong << " wrong\n";
  // Measured: 101 searches found 51, 45 refused as rivals, 3 confirmed: 6 loop constraints,
  // all wrong (where the first copy scored 0.80 against the second's 1.00, the search's spread
  // between equal places, so not a rival). Without the check, 48 loop constraints, all wrong.
  EXPECT_GT(stats.global_rivals, 30);
  EXPECT_LT(wrong, 12);
}

TEST(LoopClosureWorkerTest, ANodeOutOfOrderIsReportedAndDropped) {
  auto board = std::make_shared<LatestSolution>();
  LoopClosureWorker<HexLattice> worker(SmallSubmaps(), ScanMatcherOptions(), testing_util::SubmapGrid(3), board);
  auto node = std::make_shared<TrajectoryNode>();
  node->id = 5;
  worker.AddNode(node, {{0, Pose2()}});
  worker.Flush();
  EXPECT_NE(worker.stats().first_error.find("out of order"), std::string::npos);
  EXPECT_EQ(worker.stats().nodes, 0);
}

// The hex back end over `d`, 0.2 s between nodes, with global searches off: what closes a lap
// is the local searches alone.
std::shared_ptr<const PoseGraphSolution> RunLocalSearchesOnly(const DriftingDrive& d) {
  auto board = std::make_shared<LatestSolution>();
  LoopClosureOptions options = SmallSubmaps();
  options.constraints.global_sampling_ratio = 0.0;
  LoopClosure<HexLattice> back_end(options, ScanMatcherOptions(), testing_util::SubmapGrid(3),
                                   board);
  for (std::size_t i = 0; i < d.local.size(); ++i) {
    back_end.InsertScan(0.2 * i, d.local[i], Eigen::Vector2d::Zero(), d.points[i]);
  }
  back_end.FinishTrajectory();
  EXPECT_EQ(back_end.stats().search.global_searches, 0);
  return board->Get();
}

// Twice round the simulated building (140 m a lap) with a front end whose heading drifts by
// kBias per insertion, global searches off: local searches alone, their window grown with the
// path over which the front end may have drifted from each old submap, close a lap that drifted
// by metres. (It passes with the window grown from the last loop constraint anywhere, too: here
// the closure comes gradually, as the 30 m lidar sees the start from afar. On the MIT Killian
// Court log it did not, nor in LocalSearchesCloseALapWhoseStartComesIntoSightOnlyAtItsEnd.)
// Oracle: the truth.
TEST(LoopClosureTest, LocalSearchesAloneCloseALapThatDriftedByMetres) {
  const sim::BuildingLoop loop = sim::MakeBuildingLoop(2);
  std::mt19937_64 rng(21);
  DriftingDrive d;
  for (std::size_t i = 0; i < loop.truth.size(); i += 5) {
    d.truth.push_back(loop.truth[i]);
    d.points.push_back(testing_util::ScanPoints(loop.world, loop.truth[i], loop.lidar, &rng));
  }
  constexpr double kBias = 3e-4;  // rad per insertion
  DriftHeading(kBias, &d);
  const auto solution = RunLocalSearchesOnly(d);
  // The front end's error when the first lap ends.
  const std::size_t lap = d.truth.size() / 2;
  const double drift = (d.local[lap].translation() - d.truth[lap].translation()).norm();
  ASSERT_EQ(solution->node_poses.size(), d.truth.size());
  const double closed =
      (solution->node_poses.back().translation() - d.truth.back().translation()).norm();
  const double before = RmsError(d.local, d.truth);
  const double after = RmsError(solution->node_poses, d.truth);
  std::cout << "building, heading bias " << kBias << " rad per node: " << d.local.size()
            << " nodes, drift after a lap " << drift << " m; at the end optimised " << closed
            << " m; RMSE " << before << " -> " << after << " m\n";
  // Measured: 1.69 m after a lap (beyond the minimum window, 0.5 m, within the widest, 3 m);
  // at the end 0.012 m, RMSE 1.67 -> 0.083 m.
  EXPECT_GT(drift, 1.0);
  EXPECT_LT(drift, 3.0);
  EXPECT_LT(closed, 0.03) << "drift " << drift;
  EXPECT_LT(after, 0.1) << "before " << before;
}

// A rectangular ring, kRingWidth × kRingHeight m, driven anticlockwise from (0, 0) along x (the
// pose after `s` m of path, RingPose), lined with 0.3 m boxes scattered on both sides of the
// path, 0.6-3 m from it (three per metre: BoxRing).
constexpr double kRingWidth = 40.0, kRingHeight = 24.0;  // m

Pose2 RingPose(double s) {
  const double t = std::fmod(s, 2.0 * (kRingWidth + kRingHeight));
  if (t < kRingWidth) return Pose2(t, 0.0, 0.0);
  if (t < kRingWidth + kRingHeight) return Pose2(kRingWidth, t - kRingWidth, M_PI / 2);
  if (t < 2.0 * kRingWidth + kRingHeight) {
    return Pose2(2.0 * kRingWidth + kRingHeight - t, kRingHeight, M_PI);
  }
  return Pose2(0.0, 2.0 * (kRingWidth + kRingHeight) - t, -M_PI / 2);
}

sim::SegmentWorld BoxRing() {
  constexpr double kBox = 0.3, kNearest = 0.6, kFarthest = 3.0, kBoxesPerMetre = 3.0;
  const double lap = 2.0 * (kRingWidth + kRingHeight);
  std::mt19937_64 pattern(3);
  std::uniform_real_distribution<double> along(0.0, lap), across(kNearest, kFarthest);
  std::bernoulli_distribution left(0.5);
  sim::SegmentWorld world;
  for (int b = 0; b < static_cast<int>(kBoxesPerMetre * lap); ++b) {
    const Pose2 at = RingPose(along(pattern));
    const double side = left(pattern) ? 1.0 : -1.0;
    const Eigen::Vector2d corner = at * Eigen::Vector2d(0.0, side * across(pattern));
    world.AddRectangle(corner, corner + Eigen::Vector2d(kBox, kBox));
  }
  return world;
}

// 1.3 times round the ring with a 5 m lidar and a front end whose heading drifts kBias per node:
// the ring's start comes into sight only when the lap ends, by then 3.7 m off. All the way
// round, nodes are matched on the submaps just behind them, so loop constraints keep coming. The
// window is grown with the path since the searched submap was last tied to the trajectory (such
// matches a short way back are no revisits, and tie nothing further), and covers the lap's
// drift; grown with the path since the last loop constraint anywhere (the rule before), it
// stays at its minimum and the lap never closes (measured then: no constraint of the second lap
// on the first quarter's submaps, 2.20 m off at the end, RMSE 1.11 m). Oracle: the truth.
TEST(LoopClosureTest, LocalSearchesCloseALapWhoseStartComesIntoSightOnlyAtItsEnd) {
  constexpr double kLaps = 1.3, kStep = 0.2, kBias = 2.5e-4;  // m between nodes; rad per node
  const sim::SegmentWorld world = BoxRing();
  sim::LidarModel lidar;
  lidar.range_max = 5.0;
  std::mt19937_64 rng(21);
  DriftingDrive d;
  const double lap_metres = 2.0 * (kRingWidth + kRingHeight);
  for (double s = 0.0; s < kLaps * lap_metres; s += kStep) {
    d.truth.push_back(RingPose(s));
    d.points.push_back(testing_util::ScanPoints(world, d.truth.back(), lidar, &rng));
  }
  DriftHeading(kBias, &d);
  const auto solution = RunLocalSearchesOnly(d);
  ASSERT_EQ(solution->node_poses.size(), d.truth.size());

  const int lap = static_cast<int>(std::lround(lap_metres / kStep));
  const double drift = (d.local[lap].translation() - d.truth[lap].translation()).norm();
  // A submap's first node, from the local constraints (the nodes inserted into it).
  std::vector<int> first_node(solution->submap_poses.size(), std::numeric_limits<int>::max());
  for (const Constraint& c : solution->constraints) {
    if (c.tag == ConstraintTag::kLocal) first_node[c.submap] = std::min(first_node[c.submap], c.node);
  }
  int closing = 0;
  for (const Constraint& c : solution->constraints) {
    closing += c.tag == ConstraintTag::kLoop && c.node >= lap && first_node[c.submap] < lap / 4;
  }
  const double closed =
      (solution->node_poses.back().translation() - d.truth.back().translation()).norm();
  const double before = RmsError(d.local, d.truth);
  const double after = RmsError(solution->node_poses, d.truth);
  std::cout << "ring, 5 m lidar, heading bias " << kBias << " rad per node: drift after a lap "
            << drift << " m; " << closing << " constraints of the second lap on the first "
            << "quarter's submaps; at the end " << closed << " m; RMSE " << before << " -> "
            << after << " m\n";
  // Measured: 3.66 m after a lap; 112 closing constraints; at the end 0.44 m; RMSE 2.17 ->
  // 0.34 m (the heading bias bends the whole lap, and the graph spreads the closure over it).
  EXPECT_GT(drift, 3.0);
  EXPECT_GT(closing, 80);
  EXPECT_LT(closed, 0.6);
  EXPECT_LT(after, 0.45) << "before " << before;
}

}  // namespace
}  // namespace mapping
}  // namespace hex_slam
