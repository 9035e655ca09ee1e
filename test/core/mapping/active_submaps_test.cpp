#include "hex_slam/mapping/active_submaps.h"

#include <map>
#include <random>

#include <gtest/gtest.h>

#include "../test_maps.h"
#include "submap_grid.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {
namespace {

// Scans of the test room from a line of poses, in the local frame.
struct Scan {
  Pose2 pose;
  std::vector<Eigen::Vector2d> robot_points;
  std::vector<Eigen::Vector2d> local_points;
};

std::vector<Scan> RoomScans(int count) {
  const sim::SegmentWorld world = testing_util::GenericRoom();
  sim::LidarModel lidar;
  std::mt19937_64 rng(4);
  std::vector<Scan> scans;
  for (int i = 0; i < count; ++i) {
    Scan s;
    s.pose = testing_util::GenericPlacement() * Pose2(-2.0 + 0.2 * i, 0.1 * (i % 3), 0.05 * i);
    s.robot_points = testing_util::ScanPoints(world, s.pose, lidar, &rng);
    for (const Eigen::Vector2d& p : s.robot_points) s.local_points.push_back(s.pose * p);
    scans.push_back(s);
  }
  return scans;
}

// Two-level submap grids that reserve `reserve_radius` around a submap started alone and
// `overlap_reserve_margin` around one started beside an older one.
SubmapGridParameters ReservingGrid(double reserve_radius, double overlap_reserve_margin) {
  SubmapGridParameters grid = testing_util::SubmapGrid(2);
  grid.reserve_radius = reserve_radius;
  grid.overlap_reserve_margin = overlap_reserve_margin;
  return grid;
}

// A scan seeing farther than a small map_max_cells allows starts a submap cut to the cap around
// the sensor (and a finished one drawn again from its nodes is cut the same way), never one the
// grid refuses: the whole room is ~10 m across, the cap here a square of ~3.7 m.
TEST(ActiveSubmapsTest, AScanWiderThanTheCellCapStartsASubmapWithinIt) {
  SubmapGridParameters grid = testing_util::SubmapGrid(2);
  grid.growth.max_cells = 1 << 14;
  grid.reserve_radius = 5.0;
  SubmapOptions options;
  options.num_scans = 3;
  ActiveSubmaps<HexLattice> active(options, grid);
  const std::vector<Scan> scans = RoomScans(1);
  std::vector<std::pair<int, Pose2>> inserted;
  ASSERT_NO_THROW(active.Insert(scans[0].pose, scans[0].pose.translation(),
                                scans[0].local_points, &inserted));
  const Submap<HexLattice>* submap = active.matching_submap();
  ASSERT_NE(submap, nullptr);
  EXPECT_LE(static_cast<std::int64_t>(submap->maps().level(0).rect().size()), grid.growth.max_cells);
  const Eigen::AlignedBox2d storage = submap->maps().level(0).StorageExtent();
  EXPECT_TRUE(storage.contains(scans[0].pose.translation()));
  EXPECT_LT(storage.sizes().maxCoeff(), 8.0);  // the room's far walls are outside

  auto node = std::make_shared<TrajectoryNode>();
  node->local_pose = scans[0].pose;
  node->points = scans[0].robot_points;
  std::shared_ptr<const Submap<HexLattice>> redrawn;
  ASSERT_NO_THROW(redrawn = Submap<HexLattice>::FromNodes(0, Pose2(scans[0].pose.x, scans[0].pose.y, 0.0),
                                                          grid, {node}));
  EXPECT_LE(static_cast<std::int64_t>(redrawn->maps().level(0).rect().size()), grid.growth.max_cells);
}

// Cartographer's schedule with num_scans 3: a new submap when the newest holds 3 scans, the
// older finished when it holds 6; scans are matched against the older.
TEST(ActiveSubmapsTest, StartsFinishesAndMatchesOnCartographersSchedule) {
  SubmapOptions options;
  options.num_scans = 3;
  ActiveSubmaps<HexLattice> active(options, testing_util::SubmapGrid(2));
  EXPECT_EQ(active.matching_submap(), nullptr);
  const std::vector<Scan> scans = RoomScans(12);
  std::vector<std::vector<int>> into;
  std::vector<int> finished;
  for (int i = 0; i < 12; ++i) {
    std::vector<std::pair<int, Pose2>> inserted;
    const auto done = active.Insert(scans[i].pose, scans[i].pose.translation(),
                                    scans[i].local_points, &inserted);
    std::vector<int> ids;
    for (const auto& [id, frame] : inserted) ids.push_back(id);
    if (i == 3) {
      // A submap's frame: the position of its first scan, heading 0.
      EXPECT_DOUBLE_EQ(inserted.back().second.x, scans[3].pose.x);
      EXPECT_DOUBLE_EQ(inserted.back().second.y, scans[3].pose.y);
      EXPECT_DOUBLE_EQ(inserted.back().second.theta, 0.0);
    }
    into.push_back(ids);
    finished.push_back(done ? done->id() : -1);
    if (done) {
      EXPECT_TRUE(done->finished());
      EXPECT_EQ(done->num_scans(), 6);
    }
  }
  const std::vector<std::vector<int>> expected_into = {
      {0}, {0}, {0}, {0, 1}, {0, 1}, {0, 1}, {1, 2}, {1, 2}, {1, 2}, {2, 3}, {2, 3}, {2, 3}};
  EXPECT_EQ(into, expected_into);
  EXPECT_EQ(finished, (std::vector<int>{-1, -1, -1, -1, -1, 0, -1, -1, 1, -1, -1, 2}));
  ASSERT_NE(active.matching_submap(), nullptr);
  EXPECT_EQ(active.matching_submap()->id(), 3);
  const auto rest = active.FinishAll();
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_EQ(rest[0]->id(), 3);
  EXPECT_EQ(active.matching_submap(), nullptr);
}

// The newer submap is filled on another thread: every finished submap must hold exactly the
// cells of the same scans inserted one after another on this thread (Submap::FromNodes).
TEST(ActiveSubmapsTest, SubmapsFilledOnTheFillerThreadEqualOnesDrawnInOrder) {
  SubmapOptions options;
  options.num_scans = 3;
  SubmapGridParameters grid = testing_util::SubmapGrid(2);
  grid.reserve_radius = 2.0;
  ActiveSubmaps<HexLattice> active(options, grid);
  const std::vector<Scan> scans = RoomScans(12);
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  std::vector<std::vector<int>> members(8);
  std::vector<std::shared_ptr<const Submap<HexLattice>>> finished;
  for (int i = 0; i < 12; ++i) {
    std::vector<std::pair<int, Pose2>> inserted;
    const auto done = active.Insert(scans[i].pose, scans[i].pose.translation(),
                                    scans[i].local_points, &inserted);
    auto node = std::make_shared<TrajectoryNode>();
    node->id = i;
    node->local_pose = scans[i].pose;
    node->points = scans[i].robot_points;
    nodes.push_back(node);
    for (const auto& [id, frame] : inserted) members[id].push_back(i);
    if (done) finished.push_back(done);
  }
  for (const auto& rest : active.FinishAll()) finished.push_back(rest);
  ASSERT_EQ(finished.size(), 4u);
  for (const auto& submap : finished) {
    std::vector<std::shared_ptr<const TrajectoryNode>> own;
    for (const int n : members[submap->id()]) own.push_back(nodes[n]);
    const auto drawn =
        Submap<HexLattice>::FromNodes(submap->id(), submap->local_pose(), grid, own);
    EXPECT_EQ(submap->num_scans(), drawn->num_scans());
    for (int level = 0; level < 2; ++level) {
      const GridMap<HexLattice>& a = submap->maps().level(level);
      const GridMap<HexLattice>& b = drawn->maps().level(level);
      const GridRect both = a.rect().Union(b.rect());
      int known = 0;
      for (int row = both.min.row; row < both.min.row + both.height; ++row) {
        for (int col = both.min.col; col < both.min.col + both.width; ++col) {
          const GridIndex index{col, row};
          ASSERT_NEAR(a.LogOddsAt(index), b.LogOddsAt(index), 1e-5)
              << "submap " << submap->id() << " level " << level;
          known += a.IsKnownAt(index) ? 1 : 0;
        }
      }
      EXPECT_GT(known, 500);
    }
  }
}

// A finished submap drawn again from its nodes is the submap it was: every cell's log-odds.
template <class T>
class SubmapFromNodesTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(SubmapFromNodesTest, Lattices);

TYPED_TEST(SubmapFromNodesTest, RedrawnSubmapHasTheSameCells) {
  const std::vector<Scan> scans = RoomScans(8);
  const Pose2 frame(scans[0].pose.x, scans[0].pose.y, 0.0);
  Eigen::AlignedBox2d extent(scans[0].pose.translation());
  for (const Eigen::Vector2d& p : scans[0].local_points) extent.extend(p);
  Submap<TypeParam> original(5, frame, testing_util::SubmapGrid(2), extent);
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    original.InsertScan(scans[i].pose.translation(), scans[i].local_points);
    auto node = std::make_shared<TrajectoryNode>();
    node->id = static_cast<int>(i);
    node->local_pose = scans[i].pose;
    node->points = scans[i].robot_points;
    nodes.push_back(node);
  }
  const auto redrawn = Submap<TypeParam>::FromNodes(5, frame, testing_util::SubmapGrid(2), nodes);
  EXPECT_TRUE(redrawn->finished());
  EXPECT_EQ(redrawn->num_scans(), original.num_scans());
  for (int level = 0; level < 2; ++level) {
    const GridMap<TypeParam>& a = original.maps().level(level);
    const GridMap<TypeParam>& b = redrawn->maps().level(level);
    const GridRect both = a.rect().Union(b.rect());
    int known = 0;
    for (int row = both.min.row; row < both.min.row + both.height; ++row) {
      for (int col = both.min.col; col < both.min.col + both.width; ++col) {
        const GridIndex index{col, row};
        ASSERT_NEAR(a.LogOddsAt(index), b.LogOddsAt(index), 1e-5) << "level " << level;
        known += a.IsKnownAt(index) ? 1 : 0;
      }
    }
    EXPECT_GT(known, 1000);
  }
}

// Drawn again, a submap covers all its scans from the start: no level grows (a growth copies
// the level). The cap on a new submap's first storage (a square of ~6 m here) is smaller than
// the room (~10 m), which the whole growth allowance holds.
TYPED_TEST(SubmapFromNodesTest, ARedrawnSubmapIsSizedOnceToAllItsScans) {
  SubmapGridParameters grid = testing_util::SubmapGrid(2);
  grid.growth.max_cells = 1 << 16;
  ASSERT_LT(SubmapCapSide(grid), 8.0);
  const std::vector<Scan> scans = RoomScans(8);
  std::vector<std::shared_ptr<const TrajectoryNode>> nodes;
  Eigen::AlignedBox2d seen;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    auto node = std::make_shared<TrajectoryNode>();
    node->id = static_cast<int>(i);
    node->local_pose = scans[i].pose;
    node->points = scans[i].robot_points;
    nodes.push_back(node);
    for (const Eigen::Vector2d& p : scans[i].local_points) seen.extend(p);
  }
  ASSERT_GT(seen.sizes().maxCoeff(), SubmapCapSide(grid));
  const Pose2 frame(scans[0].pose.x, scans[0].pose.y, 0.0);
  const auto redrawn = Submap<TypeParam>::FromNodes(5, frame, grid, nodes);
  for (int level = 0; level < 2; ++level) {
    const GridMap<TypeParam>& map = redrawn->maps().level(level);
    EXPECT_EQ(map.growth_count(), 0) << "level " << level;
    EXPECT_EQ(map.points_outside(), 0) << "level " << level;
    EXPECT_TRUE(map.StorageExtent().contains(seen)) << "level " << level;
  }
}

// A new submap's reserved storage is allocated by its first insertion, on the thread that makes
// it (the filler's for the newer active submap): until then it holds its origin's cells alone.
TEST(SubmapTest, StorageIsAllocatedByTheFirstInsertion) {
  const SubmapGridParameters grid = testing_util::SubmapGrid(2);
  const Eigen::AlignedBox2d extent(Eigen::Vector2d(-3.0, -2.0), Eigen::Vector2d(4.0, 5.0));
  Submap<HexLattice> submap(0, Pose2(0.5, 0.5, 0.0), grid, extent);
  for (int k = 0; k < submap.maps().size(); ++k) {
    EXPECT_LT(submap.maps().level(k).rect().size(), 100u) << "level " << k;
  }
  submap.InsertScan({0.5, 0.5}, {{2.0, 0.5}});
  for (int k = 0; k < submap.maps().size(); ++k) {
    EXPECT_TRUE(submap.maps().level(k).StorageExtent().contains(extent)) << "level " << k;
    EXPECT_EQ(submap.maps().level(k).growth_count(), 0) << "level " << k;
  }
  const auto& finest = submap.maps().level(0);
  EXPECT_FLOAT_EQ(finest.LogOdds(finest.lattice().CellOf({2.0, 0.5})), grid.model.occupied_delta);
}

// A finished submap gives back the storage its scans did not write; an active one keeps it to
// grow into.
TEST(SubmapTest, OnlyAFinishedSubmapShrinksToWhatItsScansWrote) {
  SubmapGridParameters grid = testing_util::SubmapGrid(2);
  grid.growth.prefault = true;  // as Slam's: the memory is all of the storage
  const Eigen::AlignedBox2d extent(Eigen::Vector2d(-6.0, -6.0), Eigen::Vector2d(6.0, 6.0));
  Submap<HexLattice> submap(0, Pose2(), grid, extent);
  submap.InsertScan({0.0, 0.0}, {{1.0, 0.5}, {0.8, -0.6}});
  const std::size_t reserved = submap.maps().MemoryBytes();
  submap.ShrinkToWritten();
  EXPECT_EQ(submap.maps().MemoryBytes(), reserved);
  submap.Finish();
  submap.ShrinkToWritten();
  EXPECT_LT(submap.maps().MemoryBytes(), reserved / 10);
  const auto& finest = submap.maps().level(0);
  EXPECT_FLOAT_EQ(finest.LogOdds(finest.lattice().CellOf({1.0, 0.5})), grid.model.occupied_delta);
}

// A submap started beside an older one reserves the older's box so far (and its first scan's)
// grown by overlap_reserve_margin: in one room, later scans see the same walls, so it never grows.
TEST(ActiveSubmapsTest, ASubmapStartedBesideAnOlderOneReservesTheOldersBox) {
  const SubmapGridParameters grid = ReservingGrid(0.0, 0.5);
  SubmapOptions options;
  options.num_scans = 3;
  ActiveSubmaps<HexLattice> active(options, grid);
  const std::vector<Scan> scans = RoomScans(9);
  std::vector<std::pair<int, Pose2>> inserted;
  Eigen::AlignedBox2d older_box;
  for (int i = 0; i < 6; ++i) {
    if (i == options.num_scans) older_box = active.matching_submap()->extent();  // at the start
    active.Insert(scans[i].pose, scans[i].pose.translation(), scans[i].local_points, &inserted);
  }
  // The second submap is the older now, with three more scans in it.
  const Submap<HexLattice>* second = active.matching_submap();
  ASSERT_NE(second, nullptr);
  ASSERT_EQ(second->id(), 1);
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(grid.overlap_reserve_margin);
  const Eigen::AlignedBox2d reserved(older_box.min() - margin, older_box.max() + margin);
  for (int k = 0; k < second->maps().size(); ++k) {
    EXPECT_TRUE(second->maps().level(k).StorageExtent().contains(reserved)) << "level " << k;
    EXPECT_EQ(second->maps().level(k).growth_count(), 0) << "level " << k;
  }
  EXPECT_TRUE(reserved.contains(second->extent()));
}

// A robot driving on down a corridor: the storage the older submap needs while it is filled on
// the scan path was grown beforehand on the filler's thread (the look-ahead), so no submap grows
// while it is the one matched against, and its cells are those of its scans inserted in order.
// The scans come slower than the filler's thread inserts them (it is only asked to look ahead
// when it keeps up): each waits for the thread.
TEST(ActiveSubmapsTest, DrivingOnTheOlderSubmapNeverGrowsWhileItIsMatchedAgainst) {
  const SubmapGridParameters grid = ReservingGrid(0.5, 0.0);
  SubmapOptions options;
  options.num_scans = 20;
  ActiveSubmaps<HexLattice> active(options, grid);
  // Walls at y = ±1 m, seen up to 2 m ahead and behind; 0.4 m a scan along x.
  constexpr double kStep = 0.4, kSeen = 2.0, kPointSpacing = 0.05;
  const auto scan_at = [&](int i) {
    const Pose2 pose(kStep * i, 0.0, 0.0);
    std::vector<Eigen::Vector2d> points;
    for (double dx = -kSeen; dx <= kSeen; dx += kPointSpacing) {
      points.emplace_back(pose.x + dx, 1.0);
      points.emplace_back(pose.x + dx, -1.0);
    }
    return std::make_pair(pose, points);
  };
  std::map<int, std::vector<int>> growths_when_matched;  // by submap id, per level
  std::map<int, std::vector<std::pair<Eigen::Vector2d, std::vector<Eigen::Vector2d>>>> scans_of;
  int finished = 0;
  for (int i = 0; i < 8 * options.num_scans; ++i) {
    const auto [pose, points] = scan_at(i);
    std::vector<std::pair<int, Pose2>> inserted;
    const auto done = active.Insert(pose, pose.translation(), points, &inserted);
    active.WaitForFillerThread();
    for (const auto& [id, frame] : inserted) scans_of[id].emplace_back(pose.translation(), points);
    if (done) {
      ++finished;
      const auto matched = growths_when_matched.find(done->id());
      if (done->id() > 0) {  // the first submap is filled on the scan path from its first scan
        ASSERT_NE(matched, growths_when_matched.end());
        for (int k = 0; k < done->maps().size(); ++k) {
          EXPECT_EQ(done->maps().level(k).growth_count(), matched->second[k])
              << "submap " << done->id() << " level " << k;
        }
      }
      // The look-ahead only changed where the storage lies, not what it holds.
      Submap<HexLattice> in_order(done->id(), done->local_pose(), grid,
                                  Eigen::AlignedBox2d(done->local_pose().translation()));
      for (const auto& [origin, pts] : scans_of[done->id()]) in_order.InsertScan(origin, pts);
      for (int k = 0; k < done->maps().size(); ++k) {
        const GridMap<HexLattice>& a = done->maps().level(k);
        const GridMap<HexLattice>& b = in_order.maps().level(k);
        const GridRect both = a.rect().Union(b.rect());
        for (int row = both.min.row; row < both.min.row + both.height; ++row) {
          for (int col = both.min.col; col < both.min.col + both.width; ++col) {
            ASSERT_EQ(a.LogOddsAt({col, row}), b.LogOddsAt({col, row}))
                << "submap " << done->id() << " level " << k;
          }
        }
      }
    }
    const Submap<HexLattice>* matching = active.matching_submap();
    if (growths_when_matched.count(matching->id()) == 0) {
      std::vector<int>& counts = growths_when_matched[matching->id()];
      for (int k = 0; k < matching->maps().size(); ++k) {
        counts.push_back(matching->maps().level(k).growth_count());
      }
    }
  }
  EXPECT_EQ(finished, 7);
}

}  // namespace
}  // namespace mapping
}  // namespace hex_slam
