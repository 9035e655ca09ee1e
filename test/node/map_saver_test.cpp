#include "map_saver.h"

#include <gtest/gtest.h>

#include "hex_slam/hex_lattice.h"
#include "hex_slam/io/map_server_io.h"
#include "map_snapshot.h"
#include "temp_dir.h"

namespace hex_slam {
namespace node {
namespace {

TEST(MapSaverTest, WritesBothFormatsAndTheyLoadBack) {
  testing_util::TempDir dir;
  MapPyramid<HexLattice> maps(0.05, 2, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                              GridGrowthPolicy(),
                              Eigen::AlignedBox2d(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2)));
  std::vector<Eigen::Vector2d> wall;
  for (double y = -1.0; y <= 1.0; y += 0.02) wall.emplace_back(1.5, y);
  maps.InsertScan({0.0, 0.0}, wall);
  MapSnapshot snapshot;
  snapshot.hex.emplace(maps.level(0));
  const io::OccupancyRaster raster = RasterizeSnapshot(snapshot);

  std::vector<std::string> written;
  const std::string base = dir.File("room");
  ASSERT_EQ(SaveMapFiles(base, raster, io::CaptureHexMap(maps), &written), "");
  EXPECT_EQ(written, (std::vector<std::string>{base + ".yaml", base + ".pgm", base + ".hexmap"}));

  io::OccupancyRaster back;
  ASSERT_EQ(io::LoadMapServerMap(base + ".yaml", &back), "");
  EXPECT_EQ(back.width, raster.width);
  EXPECT_EQ(back.height, raster.height);
  EXPECT_EQ(back.data, raster.data);
  io::HexMapData cells;
  ASSERT_EQ(io::ReadHexMapFile(base + ".hexmap", &cells), "");
  EXPECT_EQ(cells.levels.size(), 2u);
  EXPECT_EQ(cells.levels[0].log_odds, maps.level(0).log_odds());
  EXPECT_EQ(dir.Files().size(), 3u);  // no temporaries left behind
}

TEST(MapSaverTest, AnUnwritablePlaceIsAnErrorAndWritesNothing) {
  io::OccupancyRaster raster;
  raster.width = raster.height = 1;
  raster.data = {-1};
  std::vector<std::string> written;
  EXPECT_NE(SaveMapFiles("/nonexistent/dir/map", raster, io::HexMapData(), &written), "");
  EXPECT_TRUE(written.empty());
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
