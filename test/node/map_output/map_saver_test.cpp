#include "map_output/map_saver.h"

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/io/map_server_io.h"
#include "hex_slam/io/occupancy_raster.h"
#include "temp_dir.h"
#include "wall_map.h"

namespace hex_slam {
namespace node {
namespace {

TEST(MapSaverTest, WritesBothFormatsAndTheyLoadBack) {
  testing_util::TempDir dir;
  MapPyramid<HexLattice> maps(0.05, 2, testing_util::HectorModel(), GridGrowthPolicy(),
                              testing_util::Square(2.0));
  testing_util::InsertWall(1.5, 1.0, &maps);
  const io::OccupancyRaster raster = io::Rasterize(maps.level(0).log_odds_grid(), 0.05);

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
  EXPECT_EQ(cells.levels[0].log_odds, maps.level(0).log_odds_grid().values());
  EXPECT_EQ(dir.Files().size(), 3u);  // no temporaries left behind
}

TEST(MapSaverTest, AYamlTargetThatIsADirectoryWritesNothingAtAll) {
  // Issue 12: the failure was reported, but the .pgm written before it stayed behind.
  testing_util::TempDir dir;
  const std::string base = dir.File("room");
  ASSERT_EQ(::mkdir((base + ".yaml").c_str(), 0755), 0);
  io::OccupancyRaster raster;
  raster.width = raster.height = 2;
  raster.resolution = 0.05;
  raster.data = {-1, 0, 100, 0};
  MapPyramid<HexLattice> maps(0.05, 2, testing_util::HectorModel(), GridGrowthPolicy(),
                              testing_util::Square(1.0));
  std::vector<std::string> written;
  const std::string error = SaveMapFiles(base, raster, io::CaptureHexMap(maps), &written);
  EXPECT_NE(error.find("room.yaml: a directory"), std::string::npos) << error;
  EXPECT_TRUE(written.empty());
  EXPECT_EQ(dir.Files(), std::vector<std::string>{"room.yaml"});  // no .pgm, .hexmap or temporary
  ::rmdir((base + ".yaml").c_str());
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
