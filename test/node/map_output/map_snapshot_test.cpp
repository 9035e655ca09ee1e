#include "map_output/map_snapshot.h"

#include <random>

#include <gtest/gtest.h>

#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/segment_world.h"

namespace hex_slam {
namespace node {
namespace {

SlamOptions SmallMap(const std::string& lattice) {
  SlamOptions options;
  options.lattice = lattice;
  options.map_size = 64;  // 3.2 m: the drive below makes it grow
  options.map_update_distance_thresh = 0.0;
  options.map_update_angle_thresh = 0.0;
  return options;
}

const MapPyramid<HexLattice>& Maps(const Slam& slam, HexLattice*) { return *slam.hex_maps(); }
const MapPyramid<SquareLattice>& Maps(const Slam& slam, SquareLattice*) {
  return *slam.square_maps();
}
const PyramidCopy<HexLattice>& Copy(const MapSnapshot& s, HexLattice*) { return *s.hex; }
const PyramidCopy<SquareLattice>& Copy(const MapSnapshot& s, SquareLattice*) { return *s.square; }

// Every cell of `copy` equals the map's (cells outside either's storage read unknown).
template <class Lattice>
void ExpectSameCells(const GridMap<Lattice>& map, const LogOddsGrid<Lattice>& copy) {
  ASSERT_EQ(copy.rect().min, map.rect().min);
  ASSERT_EQ(copy.rect().width, map.rect().width);
  ASSERT_EQ(copy.rect().height, map.rect().height);
  int known = 0;
  for (std::size_t i = 0; i < map.rect().size(); ++i) {
    const GridIndex index = map.rect().IndexAt(i);
    ASSERT_EQ(copy.LogOddsAt(index), map.LogOddsAt(index)) << index.col << " " << index.row;
    known += map.IsKnownAt(index);
  }
  EXPECT_GT(known, 100);
}

// A robot driving through a room and out of the map's initial storage: after every scan the
// snapshot is refreshed with only that scan's region (as the node does), and must equal a full
// copy of the map at every step — including after the storage grew and after a reset.
template <class Lattice>
void DriveAndCompare(const std::string& lattice) {
  sim::SegmentWorld world;
  world.AddRectangle(Eigen::Vector2d(-2.0, -1.5), Eigen::Vector2d(6.0, 1.5));
  world.AddSegment(Eigen::Vector2d(1.0, 0.8), Eigen::Vector2d(1.5, 0.9));
  sim::LidarModel lidar;
  lidar.range_max = 8.0;
  Slam slam(SmallMap(lattice));
  std::mt19937_64 rng(3);
  MapSnapshot snapshot;
  Eigen::AlignedBox2d changed;
  bool stale = true;
  std::uint64_t generation = 0;
  for (int step = 0; step < 40; ++step) {
    const Pose2 truth(0.1 * step, 0.2 * std::sin(0.3 * step), 0.05 * step);
    const ScanReport report =
        slam.ProcessScan(sim::SimulateScan(world, truth, lidar, 0.1 * step, &rng));
    if (report.map_updated) {
      changed.extend(report.updated_region);
      ++generation;
    }
    if (step % 3 == 0) {  // the map thread runs less often than the scans come
      UpdateSnapshot(slam, changed, stale, generation, 1, &snapshot);
      changed.setEmpty();
      stale = false;
      ASSERT_EQ(snapshot.generation, generation);
      const MapPyramid<Lattice>& maps = Maps(slam, static_cast<Lattice*>(nullptr));
      const PyramidCopy<Lattice>& copy = Copy(snapshot, static_cast<Lattice*>(nullptr));
      ExpectSameCells(maps.level(0), copy.finest());
      ExpectSameCells(maps.level(1), copy.drawn());
      if (step == 30) {
        EXPECT_GT(maps.level(0).growth_count(), 0) << "the drive must outgrow the storage";
        slam.Reset();
        stale = true;  // what the node sets on a reset
      }
    }
  }
}

TEST(MapSnapshotTest, RegionByRegionCopiesEqualTheHexMap) {
  DriveAndCompare<HexLattice>("hex");
}

TEST(MapSnapshotTest, RegionByRegionCopiesEqualTheSquareMap) {
  DriveAndCompare<SquareLattice>("square");
}

TEST(MapSnapshotTest, CopiesTheMapsLatticeAndClampsTheDrawnLevel) {
  const Slam hex(SmallMap("hex"));
  MapSnapshot a;
  UpdateSnapshot(hex, Eigen::AlignedBox2d(), true, 7, 9, &a);
  ASSERT_TRUE(a.hex.has_value());
  EXPECT_FALSE(a.square.has_value());
  EXPECT_EQ(a.generation, 7u);
  EXPECT_EQ(a.hex->drawn_level(), hex.hex_maps()->size() - 1);
  EXPECT_DOUBLE_EQ(a.hex->finest().lattice().spacing(),
                   hex.hex_maps()->level(0).lattice().spacing());
  const Slam square(SmallMap("square"));
  MapSnapshot b;
  UpdateSnapshot(square, Eigen::AlignedBox2d(), true, 1, 0, &b);
  EXPECT_FALSE(b.hex.has_value());
  ASSERT_TRUE(b.square.has_value());
  EXPECT_EQ(&b.square->drawn(), &b.square->finest());
}

TEST(MapSnapshotTest, AnEmptyMapGivesOneUnknownPixelAtTheAskedResolution) {
  MapSnapshot snapshot;
  UpdateSnapshot(Slam(SmallMap("hex")), Eigen::AlignedBox2d(), true, 0, 1, &snapshot);
  const io::OccupancyRaster raster = RasterizeSnapshot(snapshot, 0.05);
  EXPECT_EQ(raster.width, 1);
  EXPECT_EQ(raster.height, 1);
  EXPECT_EQ(raster.data, std::vector<std::int8_t>{io::OccupancyRaster::kUnknown});
  EXPECT_DOUBLE_EQ(raster.resolution, 0.05);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
