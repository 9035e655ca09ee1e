#include "map_snapshot.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

SlamOptions SmallMap(const std::string& lattice) {
  SlamOptions options;
  options.lattice = lattice;
  options.map_size = 64;
  return options;
}

TEST(MapSnapshotTest, CopiesTheFinestLevelOfTheMapsLattice) {
  const Slam hex(SmallMap("hex"));
  const MapSnapshot a = TakeSnapshot(hex, 7);
  EXPECT_TRUE(a.hex.has_value());
  EXPECT_FALSE(a.square.has_value());
  EXPECT_EQ(a.generation, 7u);
  EXPECT_DOUBLE_EQ(a.hex->lattice().spacing(), hex.hex_maps()->level(0).lattice().spacing());
  EXPECT_EQ(a.hex->rect().size(), hex.hex_maps()->level(0).rect().size());
  const Slam square(SmallMap("square"));
  const MapSnapshot b = TakeSnapshot(square, 1);
  EXPECT_FALSE(b.hex.has_value());
  EXPECT_TRUE(b.square.has_value());
}

TEST(MapSnapshotTest, RastersAtEqualAreaAndAnEmptyMapGivesOneUnknownPixel) {
  const MapSnapshot snapshot = TakeSnapshot(Slam(SmallMap("hex")), 0);
  const io::OccupancyRaster raster = RasterizeSnapshot(snapshot);
  EXPECT_EQ(raster.width, 1);
  EXPECT_EQ(raster.height, 1);
  EXPECT_EQ(raster.data, std::vector<std::int8_t>{io::OccupancyRaster::kUnknown});
  EXPECT_NEAR(raster.resolution, std::sqrt(HexLattice(0.05).cell_area()), 1e-12);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
