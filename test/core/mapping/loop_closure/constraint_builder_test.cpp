#include "hex_slam/mapping/loop_closure/constraint_builder.h"

#include <random>

#include <gtest/gtest.h>

#include "../../test_maps.h"
#include "../submap_grid.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {
namespace {

template <class T>
class ConstraintBuilderTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(ConstraintBuilderTest, Lattices);

std::shared_ptr<TrajectoryNode> NodeAt(const sim::World& world, const Pose2& pose, int id,
                                       std::mt19937_64* rng) {
  sim::LidarModel lidar;
  lidar.beams = 360;
  auto node = std::make_shared<TrajectoryNode>();
  node->id = id;
  node->local_pose = pose;
  node->points = testing_util::ScanPoints(world, pose, lidar, rng);
  return node;
}

// A finished submap of `world` from scans at `poses` (world = local frame), its frame at the
// first pose's position.
template <class Lattice>
std::shared_ptr<const Submap<Lattice>> SubmapOf(const sim::World& world,
                                                const std::vector<Pose2>& poses) {
  std::mt19937_64 rng(8);
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  for (const Pose2& p : poses) nodes.push_back(NodeAt(world, p, 0, &rng));
  return Submap<Lattice>::FromNodes(0, Pose2(poses[0].x, poses[0].y, 0.0), testing_util::SubmapGrid(3), nodes);
}

// The constraint is the node's true pose in the submap's frame, from a guess half a metre and
// five degrees off, to within a centimetre and a few milliradians (Gauss–Newton's refinement of
// a branch-and-bound pose a cell and an angular step coarse).
TYPED_TEST(ConstraintBuilderTest, FindsTheTruePoseOfANodeInASubmap) {
  const sim::SegmentWorld world = testing_util::GenericRoom();
  const Pose2& g = testing_util::GenericPlacement();
  const auto submap = SubmapOf<TypeParam>(
      world, {g * Pose2(0, 0, 0), g * Pose2(-2.5, 1.0, 0.3), g * Pose2(3.2, -0.5, -1.0),
              g * Pose2(-3.5, -2.0, 2.0), g * Pose2(2.5, 3.0, 0.7)});
  ConstraintBuilderOptions options;
  const matching::FastCorrelativeScanMatcher<TypeParam> matcher(submap->maps().level(0),
                                                                options.matcher);
  ConstraintBuilder<TypeParam> builder(options, ScanMatcherOptions());
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int refused = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Pose2 truth = g * Pose2(1.5 * u(rng), 1.5 * u(rng), M_PI * u(rng));
    const auto node = NodeAt(world, truth, 7, &rng);
    const Pose2 in_submap = RelativePose(submap->local_pose(), truth);
    const Pose2 expected = in_submap * Pose2(0.35 * u(rng), 0.35 * u(rng), 0.09 * u(rng));
    const std::optional<Constraint> c =
        builder.Search(*submap, matcher, *node, expected, 10.0, false);
    ASSERT_TRUE(c.has_value()) << "trial " << trial;
    EXPECT_EQ(c->submap, 0);
    EXPECT_EQ(c->node, 7);
    EXPECT_EQ(c->tag, ConstraintTag::kLoop);
    EXPECT_LT((c->relative.translation() - in_submap.translation()).norm(), 0.01)
        << "trial " << trial;
    EXPECT_LT(std::abs(NormalizeAngle(c->relative.theta - in_submap.theta)), 0.004)
        << "trial " << trial;
    // And from anywhere: the full-submap search finds the same pose, or refuses it because the
    // room (a rectangle) turned by pi fits the scan nearly as well.
    const std::optional<Constraint> global =
        builder.Search(*submap, matcher, *node, Pose2(), 0.0, true);
    if (!global) {
      std::vector<Eigen::Vector2d> searched;
      DecimateScan(node->points, options.point_spacing, &searched);
      const std::optional<matching::CorrelativeMatch> m =
          matcher.MatchFullSubmap(searched, options.global_localization_min_score);
      ASSERT_TRUE(m.has_value()) << "trial " << trial;
      EXPECT_GT(m->runner_up_score, 0.0) << "trial " << trial;
      EXPECT_GT(std::abs(NormalizeAngle(m->runner_up_pose.theta - m->pose.theta)), M_PI / 2)
          << "trial " << trial;
      ++refused;
      continue;
    }
    EXPECT_LT((global->relative.translation() - in_submap.translation()).norm(), 0.01);
  }
  EXPECT_EQ(builder.stats().local_searches, 6);
  EXPECT_EQ(builder.stats().local_found, 6);
  EXPECT_EQ(builder.stats().global_found + refused, 6);
  EXPECT_LE(refused, 1);
}

TYPED_TEST(ConstraintBuilderTest, AScanOfAnotherPlaceGivesNoConstraint) {
  const sim::SegmentWorld room = testing_util::GenericRoom();
  const Pose2& g = testing_util::GenericPlacement();
  const auto submap = SubmapOf<TypeParam>(room, {g * Pose2(-2.5, 1.0, 0.3), g * Pose2(2.5, 3.0, 0.7)});
  ConstraintBuilderOptions options;
  const matching::FastCorrelativeScanMatcher<TypeParam> matcher(submap->maps().level(0),
                                                                options.matcher);
  ConstraintBuilder<TypeParam> builder(options, ScanMatcherOptions());
  std::mt19937_64 rng(10);
  // A long empty corridor is nothing like the room.
  sim::SegmentWorld corridor;
  corridor.AddRectangle({-20.0, -0.8}, {20.0, 0.8});
  const auto node = NodeAt(corridor, Pose2(), 3, &rng);
  EXPECT_FALSE(builder.Search(*submap, matcher, *node, RelativePose(submap->local_pose(), g), 50.0,
                              false)
                   .has_value());
  EXPECT_FALSE(builder.Search(*submap, matcher, *node, Pose2(), 0.0, true).has_value());
}

// Two copies of a room side by side: a scan from inside one fits the other as well, so the
// match is refused rather than taken for either.
TYPED_TEST(ConstraintBuilderTest, AScanThatFitsTwoPlacesIsRefusedAsAmbiguous) {
  sim::SegmentWorld twins;
  for (const double x : {0.0, 6.0}) {
    twins.AddRectangle({x - 2.0, -1.5}, {x + 2.0, 1.5});
    twins.AddRectangle({x + 0.5, 0.3}, {x + 1.1, 0.8});
    twins.AddRectangle({x - 1.4, -1.0}, {x - 0.9, -0.6});
  }
  const auto submap = SubmapOf<TypeParam>(twins, {Pose2(0.0, 0.0, 0.0), Pose2(6.0, 0.0, 0.0)});
  ConstraintBuilderOptions options;
  options.matcher.linear_search_window = 8.0;
  const matching::FastCorrelativeScanMatcher<TypeParam> matcher(submap->maps().level(0),
                                                                options.matcher);
  ConstraintBuilder<TypeParam> builder(options, ScanMatcherOptions());
  std::mt19937_64 rng(11);
  const Pose2 truth(0.2, -0.3, 0.4);
  const auto node = NodeAt(twins, truth, 1, &rng);
  const Pose2 expected = RelativePose(submap->local_pose(), truth);
  // 150 m since the last loop constraint: the window is at its widest, 8 m, and holds both rooms.
  EXPECT_FALSE(builder.Search(*submap, matcher, *node, expected, 150.0, false).has_value());
  EXPECT_EQ(builder.stats().ambiguous, 1);
  // Right after one it is half a metre wide: one place, and the match stands.
  EXPECT_TRUE(builder.Search(*submap, matcher, *node, expected, 0.0, false).has_value());
}

TEST(ConstraintBuilderOptionsTest, WindowGrowsWithTheDistanceSinceTheLastLoopUpToItsCap) {
  ConstraintBuilderOptions options;
  options.min_linear_search_window = 0.5;
  options.search_window_growth = 0.05;
  options.matcher.linear_search_window = 3.0;
  const ConstraintBuilder<HexLattice> builder(options, ScanMatcherOptions());
  EXPECT_DOUBLE_EQ(builder.LinearWindow(0.0), 0.5);
  EXPECT_DOUBLE_EQ(builder.LinearWindow(20.0), 1.5);
  EXPECT_DOUBLE_EQ(builder.LinearWindow(1000.0), 3.0);
  EXPECT_DOUBLE_EQ(builder.AngularWindow(0.0), options.min_angular_search_window);
  EXPECT_DOUBLE_EQ(builder.AngularWindow(1000.0), options.matcher.angular_search_window);
  options.sampling_ratio = 1.5;
  options.point_spacing = -1.0;
  const std::vector<std::string> errors = options.Validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("loop_closure_sampling_ratio"), std::string::npos);
}

}  // namespace
}  // namespace mapping
}  // namespace hex_slam
