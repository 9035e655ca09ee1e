#include "hex_slam/mapping/loop_closure/submap_cache.h"

#include <random>

#include <gtest/gtest.h>

#include "../../test_maps.h"
#include "../submap_grid.h"
#include "hex_slam/geometry/hex_lattice.h"

namespace hex_slam {
namespace mapping {
namespace {

// Submap `id` drawn from three scans of the test room around `centre`.
std::shared_ptr<const Submap<HexLattice>> RoomSubmap(int id, const Pose2& centre) {
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(id);
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  for (int i = 0; i < 3; ++i) {
    auto node = std::make_shared<TrajectoryNode>();
    node->id = i;
    node->local_pose = centre * Pose2(0.2 * i, 0.0, 0.1 * i);
    node->points = testing_util::ScanPoints(world, node->local_pose, lidar, &rng);
    nodes.push_back(node);
  }
  return Submap<HexLattice>::FromNodes(id, Pose2(centre.x, centre.y, 0.0),
                                       testing_util::SubmapGrid(3), nodes);
}

// A budget that holds one pyramid and three global search grids but not two pyramids: a second
// pyramid drops the first one's, although its grids were used less recently (a search needs
// grids; a pyramid only refines its matches), and the grids held are those the pyramid gives.
TEST(SubmapCacheTest, SearchGridsOutliveTheirPyramid) {
  const Pose2 centre = testing_util::GenericPlacement();
  const auto a = RoomSubmap(0, centre);
  const auto b = RoomSubmap(1, centre * Pose2(0.5, 0.0, 0.0));
  const matching::FastCorrelativeScanMatcherOptions options;
  const std::size_t maps_bytes = std::max(a->maps().MemoryBytes(), b->maps().MemoryBytes());
  const std::size_t grid_bytes =
      SubmapCache<HexLattice>::Matcher(a->maps().level(2), options).MemoryBytes();
  ASSERT_LT(grid_bytes * 4, maps_bytes);  // the premise: a coarse level's grids are small
  SubmapCache<HexLattice> cache(maps_bytes + 3 * grid_bytes, options, 1, 2);

  cache.AddMaps(a);
  const auto grids_a = cache.AddMatcher(*a, true);
  EXPECT_EQ(cache.FindMatcher(0, true), grids_a);
  EXPECT_EQ(cache.FindMatcher(0, false), nullptr);  // local grids are another part
  EXPECT_EQ(cache.FindMaps(0), a);  // now a's grids are the least recently used

  cache.AddMaps(b);  // over the budget: a pyramid goes first
  EXPECT_EQ(cache.FindMaps(0), nullptr);
  EXPECT_EQ(cache.FindMaps(1), b);
  EXPECT_EQ(cache.FindMatcher(0, true), grids_a);
  EXPECT_LE(cache.bytes(), maps_bytes + 3 * grid_bytes);
  EXPECT_EQ(cache.matchers_built(), 1);

  // The held grids are a's: they find a's own node where a search on fresh grids does.
  const SubmapCache<HexLattice>::Matcher fresh(a->maps().level(2), options);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(9);
  const Pose2 truth = centre * Pose2(0.2, 0.0, 0.1);
  const std::vector<Eigen::Vector2d> points = testing_util::ScanPoints(world, truth, lidar, &rng);
  const auto held = grids_a->MatchFullSubmap(points, 0.5);
  const auto again = fresh.MatchFullSubmap(points, 0.5);
  ASSERT_TRUE(held.has_value());
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(held->pose.x, again->pose.x);
  EXPECT_EQ(held->pose.y, again->pose.y);
  EXPECT_EQ(held->pose.theta, again->pose.theta);
  EXPECT_LT((held->pose.translation() - truth.translation()).norm(), 0.3);
}

// The part just added stays even when it alone is over the budget: it is about to be used.
TEST(SubmapCacheTest, TheNewestPartStaysOverTheBudget) {
  const auto a = RoomSubmap(0, testing_util::GenericPlacement());
  SubmapCache<HexLattice> cache(1, matching::FastCorrelativeScanMatcherOptions(), 1, 2);
  cache.AddMaps(a);
  EXPECT_EQ(cache.FindMaps(0), a);
  const auto grids = cache.AddMatcher(*a, false);
  EXPECT_EQ(cache.FindMaps(0), nullptr);
  EXPECT_EQ(cache.FindMatcher(0, false), grids);
}

}  // namespace
}  // namespace mapping
}  // namespace hex_slam
