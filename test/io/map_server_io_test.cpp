#include "hex_slam/io/map_server_io.h"

#include <fstream>

#include <gtest/gtest.h>

#include "hex_slam/io/image_io.h"
#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

OccupancyRaster SmallRaster() {
  OccupancyRaster raster;
  raster.resolution = 0.05;
  raster.origin = Eigen::Vector2d(-1.25, 2.5);
  raster.width = 4;
  raster.height = 3;
  raster.data = {100, 0, -1, 0,  //
                 0,   0, 0,  -1,  //
                 -1, 100, 100, 0};
  return raster;
}

TEST(MapServerIoTest, SaveThenLoadGivesTheSameMap) {
  testing_util::TempDir dir;
  const OccupancyRaster raster = SmallRaster();
  ASSERT_EQ(SaveMapServerMap(raster, dir.File("map")), "");
  OccupancyRaster back;
  ASSERT_EQ(LoadMapServerMap(dir.File("map.yaml"), &back), "");
  EXPECT_EQ(back.width, raster.width);
  EXPECT_EQ(back.height, raster.height);
  EXPECT_DOUBLE_EQ(back.resolution, raster.resolution);
  EXPECT_NEAR((back.origin - raster.origin).norm(), 0.0, 1e-6);
  EXPECT_EQ(back.data, raster.data);
  // Row 0 of the raster is the bottom of the image: the file's last row.
  Image image;
  ASSERT_EQ(ReadGrayImage(dir.File("map.pgm"), &image), "");
  EXPECT_EQ(*image.at(0, 2), MapServerFormat::kOccupiedGray);
  EXPECT_EQ(*image.at(2, 2), MapServerFormat::kUnknownGray);
  EXPECT_EQ(*image.at(0, 0), MapServerFormat::kUnknownGray);
}

TEST(MapServerIoTest, NegateAndScaleModesFollowMapServer) {
  testing_util::TempDir dir;
  Image image(3, 1, 1);
  image.pixels = {0, 128, 255};
  ASSERT_EQ(WritePgm(dir.File("m.pgm"), image), "");
  std::ofstream(dir.File("m.yaml")) << "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
                                       "negate: 1\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  OccupancyRaster raster;
  ASSERT_EQ(LoadMapServerMap(dir.File("m.yaml"), &raster), "");
  EXPECT_EQ(raster.data, (std::vector<std::int8_t>{0, -1, 100}));
  std::ofstream(dir.File("s.yaml")) << "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
                                       "mode: scale\n";
  ASSERT_EQ(LoadMapServerMap(dir.File("s.yaml"), &raster), "");
  EXPECT_EQ(raster.data[0], 100);
  EXPECT_EQ(raster.data[2], 0);
  EXPECT_GT(raster.data[1], 0);
  EXPECT_LT(raster.data[1], 100);
}

TEST(MapServerIoTest, BrokenYamlIsAClearError) {
  testing_util::TempDir dir;
  OccupancyRaster raster;
  EXPECT_NE(LoadMapServerMap(dir.File("none.yaml"), &raster), "");
  std::ofstream(dir.File("a.yaml")) << "image: [unclosed\n";
  EXPECT_NE(LoadMapServerMap(dir.File("a.yaml"), &raster), "");
  std::ofstream(dir.File("b.yaml")) << "image: x.pgm\nresolution: 0.1\n";
  EXPECT_NE(LoadMapServerMap(dir.File("b.yaml"), &raster).find("origin"), std::string::npos);
  std::ofstream(dir.File("c.yaml")) << "image: missing.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  EXPECT_NE(LoadMapServerMap(dir.File("c.yaml"), &raster).find("missing.pgm"), std::string::npos);
  std::ofstream(dir.File("d.yaml")) << "image: m.pgm\nresolution: fast\norigin: [0, 0, 0]\n"
                                       "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  EXPECT_NE(LoadMapServerMap(dir.File("d.yaml"), &raster).find("resolution"), std::string::npos);
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
