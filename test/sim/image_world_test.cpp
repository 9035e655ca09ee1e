#include "hex_slam/sim/image_world.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/io/image_io.h"
#include "hex_slam/sim/scenario.h"
#include "hex_slam/sim/segment_world.h"

namespace hex_slam {
namespace sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

io::OccupancyRaster EmptyRaster(int width, int height, double resolution,
                                const Eigen::Vector2d& origin) {
  io::OccupancyRaster r;
  r.resolution = resolution;
  r.origin = origin;
  r.width = width;
  r.height = height;
  r.data.assign(static_cast<std::size_t>(width) * height, io::OccupancyRaster::kFree);
  return r;
}

void Fill(io::OccupancyRaster* r, int c0, int r0, int c1, int r1, std::int8_t value) {
  for (int row = r0; row < r1; ++row) {
    for (int col = c0; col < c1; ++col) r->data[static_cast<std::size_t>(row) * r->width + col] = value;
  }
}

// The exact first hit by brute force: the ray against every solid pixel's square (slab test).
double BruteForce(const ImageWorld& world, const Eigen::Vector2d& origin, double angle,
                  double max_range) {
  const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
  double best = kInf;
  for (int row = 0; row < world.height(); ++row) {
    for (int col = 0; col < world.width(); ++col) {
      if (!world.IsSolid(col, row)) continue;
      const Eigen::Vector2d lo = world.origin() + world.resolution() * Eigen::Vector2d(col, row);
      const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(world.resolution());
      double t0 = 0.0, t1 = kInf;
      bool hit = true;
      for (int k = 0; k < 2 && hit; ++k) {
        if (dir[k] == 0.0) {
          hit = origin[k] >= lo[k] && origin[k] < hi[k];
          continue;
        }
        double a = (lo[k] - origin[k]) / dir[k], b = (hi[k] - origin[k]) / dir[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        hit = t0 <= t1;
      }
      if (hit && t1 > t0 && t0 < best) best = t0;
    }
  }
  return best <= max_range ? best : kInf;
}

TEST(ImageWorldTest, RectangleOfPixelsCastsLikeTheSameRectangleOfSegments) {
  // A 4 m x 3 m room whose inner wall faces lie on pixel boundaries (2 cm pixels, walls 3 px).
  const double res = 0.02;
  const Eigen::Vector2d origin(-1.3, 0.7);
  io::OccupancyRaster raster = EmptyRaster(206, 156, res, origin);
  Fill(&raster, 0, 0, 206, 3, io::OccupancyRaster::kOccupied);
  Fill(&raster, 0, 153, 206, 156, io::OccupancyRaster::kOccupied);
  Fill(&raster, 0, 0, 3, 156, io::OccupancyRaster::kOccupied);
  Fill(&raster, 203, 0, 206, 156, io::OccupancyRaster::kOccupied);
  const ImageWorld image(raster, ImageWorldOptions());
  SegmentWorld segments;
  segments.AddRectangle(origin + Eigen::Vector2d(3 * res, 3 * res),
                        origin + Eigen::Vector2d(203 * res, 153 * res));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(origin.x() + 0.1, origin.x() + 3.9);
  std::uniform_real_distribution<double> uy(origin.y() + 0.1, origin.y() + 2.9);
  std::uniform_real_distribution<double> ua(-M_PI, M_PI);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    const double a = ua(rng);
    ASSERT_NEAR(image.CastRay(p, a, 10.0), segments.CastRay(p, a, 10.0), 1e-9)
        << "ray " << i << " from " << p.transpose() << " at " << a;
  }
  // Axis-aligned rays, where a walk can go wrong on boundaries.
  for (double a : {0.0, 0.5 * M_PI, M_PI, -0.5 * M_PI}) {
    const Eigen::Vector2d p = origin + Eigen::Vector2d(1.0, 1.0);
    EXPECT_NEAR(image.CastRay(p, a, 10.0), segments.CastRay(p, a, 10.0), 1e-9) << a;
  }
}

TEST(ImageWorldTest, MatchesBruteForceOnRandomPixels) {
  std::mt19937_64 rng(11);
  io::OccupancyRaster raster = EmptyRaster(40, 30, 0.05, Eigen::Vector2d(0.3, -0.2));
  std::bernoulli_distribution solid(0.04);
  for (auto& v : raster.data) v = solid(rng) ? io::OccupancyRaster::kOccupied : 0;
  const ImageWorld world(raster, ImageWorldOptions());
  // Origins inside and outside the image, ranges long and short.
  std::uniform_real_distribution<double> ux(-0.5, 2.8), uy(-1.0, 2.0), ua(-M_PI, M_PI);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    const double a = ua(rng);
    const double range = i % 3 == 0 ? 0.4 : 5.0;
    const double expected = BruteForce(world, p, a, range);
    const double got = world.CastRay(p, a, range);
    if (std::isinf(expected)) {
      ASSERT_TRUE(std::isinf(got)) << i << ": got " << got;
    } else {
      ASSERT_NEAR(got, expected, 1e-9) << i;
      ++hits;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST(ImageWorldTest, InsideASolidPixelReadsZeroAndOutsideIsFree) {
  io::OccupancyRaster raster = EmptyRaster(10, 10, 0.1, Eigen::Vector2d::Zero());
  Fill(&raster, 5, 5, 6, 6, io::OccupancyRaster::kOccupied);
  const ImageWorld world(raster, ImageWorldOptions());
  EXPECT_EQ(world.CastRay({0.55, 0.55}, 1.0, 5.0), 0.0);
  EXPECT_TRUE(world.IsSolidAt({0.55, 0.58}));
  EXPECT_FALSE(world.IsSolidAt({5.0, 5.0}));
  // From outside the image towards the pixel: the hit is at its boundary.
  EXPECT_NEAR(world.CastRay({-1.0, 0.55}, 0.0, 5.0), 1.5, 1e-12);
  EXPECT_TRUE(std::isinf(world.CastRay({-1.0, 0.55}, 0.0, 1.4)));  // beyond max_range
  EXPECT_TRUE(std::isinf(world.CastRay({-1.0, 0.55}, M_PI, 5.0)));  // away from the image
  EXPECT_TRUE(std::isinf(world.CastRay({0.15, 0.15}, 0.0, 5.0)));   // leaves without a hit
}

TEST(ImageWorldTest, UnknownPixelsAreSolidOnlyWhenAsked) {
  io::OccupancyRaster raster = EmptyRaster(10, 1, 0.1, Eigen::Vector2d::Zero());
  raster.data[7] = io::OccupancyRaster::kUnknown;
  raster.data[9] = 60;  // above the default threshold
  ImageWorldOptions options;
  EXPECT_NEAR(ImageWorld(raster, options).CastRay({0.05, 0.05}, 0.0, 5.0), 0.85, 1e-12);
  options.unknown_is_occupied = true;
  EXPECT_NEAR(ImageWorld(raster, options).CastRay({0.05, 0.05}, 0.0, 5.0), 0.65, 1e-12);
  options.occupied_threshold = 70;
  options.unknown_is_occupied = false;
  EXPECT_TRUE(std::isinf(ImageWorld(raster, options).CastRay({0.05, 0.05}, 0.0, 5.0)));
}

TEST(ImageWorldTest, RejectsInconsistentRasters) {
  io::OccupancyRaster raster = EmptyRaster(4, 4, 0.1, Eigen::Vector2d::Zero());
  raster.data.pop_back();
  EXPECT_THROW(ImageWorld(raster, ImageWorldOptions()), std::invalid_argument);
  raster = EmptyRaster(4, 4, 0.0, Eigen::Vector2d::Zero());
  EXPECT_THROW(ImageWorld(raster, ImageWorldOptions()), std::invalid_argument);
}

TEST(ImageWorldTest, LoadsTheShippedMaze) {
  ImageWorld world;
  ASSERT_EQ(LoadImageWorld(std::string(HEX_SLAM_SOURCE_DIR) + "/worlds/maze.yaml",
                           ImageWorldOptions(), &world),
            "");
  EXPECT_EQ(world.width(), 540);
  EXPECT_EQ(world.height(), 540);
  EXPECT_DOUBLE_EQ(world.resolution(), 0.01);
  // From the middle of the entrance cell the top outer wall (inner face at 5.38 m) is 0.43 m up.
  EXPECT_NEAR(world.CastRay({0.45, 4.95}, 0.5 * M_PI, 8.0), 0.43, 1e-9);
  // The entrance is open to the left.
  EXPECT_TRUE(std::isinf(world.CastRay({0.45, 4.95}, M_PI, 8.0)));
}

TEST(ImageWorldTest, LoadErrorsNameTheFile) {
  ImageWorld world;
  EXPECT_NE(LoadImageWorld("/nonexistent/world.yaml", ImageWorldOptions(), &world).find(
                "/nonexistent/world.yaml"),
            std::string::npos);
  const std::string error = LoadBitmapWorld("/nonexistent/maze.png", 0.01, {0, 0}, &world);
  EXPECT_NE(error.find("/nonexistent/maze.png"), std::string::npos) << error;
  EXPECT_FALSE(LoadBitmapWorld("/nonexistent/maze.png", 0.0, {0, 0}, &world).empty());
}

TEST(ImageWorldTest, BitmapDarkPixelsAreSolid) {
  io::Image image(3, 2, 1, 255);
  *image.at(2, 0) = 0;    // top-right: row 1 of the world (rows count from the bottom)
  *image.at(0, 1) = 100;  // bottom-left
  const std::string path = ::testing::TempDir() + "/hex_slam_bitmap_test.png";
  ASSERT_EQ(io::WritePng(path, image), "");
  ImageWorld world;
  ASSERT_EQ(LoadBitmapWorld(path, 0.5, {1.0, 2.0}, &world), "");
  EXPECT_TRUE(world.IsSolid(2, 1));
  EXPECT_TRUE(world.IsSolid(0, 0));
  EXPECT_FALSE(world.IsSolid(1, 0));
  EXPECT_TRUE(world.IsSolidAt({2.25, 2.75}));
  std::remove(path.c_str());
}

TEST(ImageWorldTest, ThePapersMazeWhenPresent) {
  const std::string bitmap =
      DataDirectory(HEX_SLAM_SOURCE_DIR) + "/robotcraft_maze/540x540-90cm.png";
  if (!std::ifstream(bitmap)) GTEST_SKIP() << "the paper's maze bitmap is absent: " << bitmap;
  ImageWorld world;
  ASSERT_EQ(LoadBitmapWorld(bitmap, 0.01, {0, 0}, &world), "");
  // stage's start pose sits in the open entrance, between the outer wall (inner face at 5.38 m)
  // and the first inner wall (4.49-4.51 m).
  EXPECT_NEAR(world.CastRay({0.05, 4.95}, 0.5 * M_PI, 8.0), 0.43, 1e-9);
  EXPECT_NEAR(world.CastRay({0.05, 4.95}, -0.5 * M_PI, 8.0), 0.44, 1e-9);
  EXPECT_TRUE(std::isinf(world.CastRay({0.05, 4.95}, M_PI, 8.0)));
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
