// hex_slam_demo: the built-in scenario, run end to end without ROS. Simulates the room drive,
// runs SLAM on the hex lattice and on the square baseline at equal cell area, prints each one's
// error against ground truth, and writes the hex map as map_server PGM+YAML, a PNG of that
// raster, and a PNG of the hexagons themselves.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "hex_slam/io/image_io.h"
#include "hex_slam/io/map_image.h"
#include "hex_slam/io/map_server_io.h"
#include "hex_slam/io/occupancy_raster.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/slam.h"

namespace hex_slam {
namespace {

struct Args {
  std::string out = "out/demo";
  int beams = 360;
  double resolution = 0.05;
  double noise = 0.01;
  unsigned seed = 1;
};

void Usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s [--out DIR] [--beams N] [--resolution D] [--noise SIGMA] [--seed S]\n"
               "  Simulates a drive through a 10 m x 8 m room and maps it on the hex lattice\n"
               "  (centre spacing D, default 0.05 m) and the square one of equal cell area.\n",
               argv0);
}

bool Parse(int argc, char** argv, Args* args) {
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (i + 1 >= argc) return false;
    const char* value = argv[++i];
    if (key == "--out") {
      args->out = value;
    } else if (key == "--beams") {
      args->beams = std::atoi(value);
    } else if (key == "--resolution") {
      args->resolution = std::atof(value);
    } else if (key == "--noise") {
      args->noise = std::atof(value);
    } else if (key == "--seed") {
      args->seed = static_cast<unsigned>(std::atoi(value));
    } else {
      return false;
    }
  }
  return args->beams >= 3 && args->resolution > 0.0 && args->noise >= 0.0;
}

struct RunResult {
  double position_rmse = 0.0;
  double position_max = 0.0;
  double angle_rmse = 0.0;
  double ms_per_scan = 0.0;
  int scans = 0;
};

RunResult Run(const sim::RoomDrive& drive, const SlamOptions& options, unsigned seed, Slam* slam) {
  std::mt19937_64 rng(seed);
  slam->Reset(drive.truth.front());
  RunResult result;
  double sum_sq = 0.0, sum_sq_angle = 0.0, seconds = 0.0;
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    const LaserScan scan =
        sim::SimulateScan(drive.world, drive.truth[i], drive.lidar, drive.scan_period * i, &rng);
    const auto start = std::chrono::steady_clock::now();
    const ScanReport report = slam->ProcessScan(scan);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double e = (report.pose.translation() - drive.truth[i].translation()).norm();
    const double a = NormalizeAngle(report.pose.theta - drive.truth[i].theta);
    sum_sq += e * e;
    sum_sq_angle += a * a;
    result.position_max = std::max(result.position_max, e);
  }
  (void)options;
  result.scans = static_cast<int>(drive.truth.size());
  result.position_rmse = std::sqrt(sum_sq / result.scans);
  result.angle_rmse = std::sqrt(sum_sq_angle / result.scans);
  result.ms_per_scan = 1e3 * seconds / result.scans;
  return result;
}

io::Image ToImage(const io::OccupancyRaster& raster) {
  io::Image image(raster.width, raster.height, 1);
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const int v = raster.at(col, row);
      *image.at(col, raster.height - 1 - row) = v < 0 ? 205 : v >= 50 ? 0 : 254;
    }
  }
  return image;
}

int Main(int argc, char** argv) {
  Args args;
  if (!Parse(argc, argv, &args)) {
    Usage(argv[0]);
    return 2;
  }
  std::error_code dir_error;
  std::filesystem::create_directories(args.out, dir_error);
  if (dir_error) {
    std::fprintf(stderr, "error: cannot create %s: %s\n", args.out.c_str(),
                 dir_error.message().c_str());
    return 1;
  }
  const sim::RoomDrive drive = sim::MakeRoomDrive(args.beams, args.noise);
  std::printf("hex_slam demo: %zu scans of a %d-beam lidar (noise %.3f m) along a loop through a "
              "10 m x 8 m room\n",
              drive.truth.size(), args.beams, args.noise);

  SlamOptions hex_options;
  hex_options.map_resolution = args.resolution;
  SlamOptions square_options = hex_options;
  square_options.lattice = "square";
  square_options.map_resolution = std::sqrt(HexLattice(args.resolution).cell_area());
  Slam hex(hex_options), square(square_options);
  const RunResult h = Run(drive, hex_options, args.seed, &hex);
  const RunResult s = Run(drive, square_options, args.seed, &square);
  std::printf("\n%-8s %10s %14s %12s %13s %12s\n", "lattice", "cell_m", "pos_rmse_m", "pos_max_m",
              "angle_rmse", "ms/scan");
  std::printf("%-8s %10.4f %14.4f %12.4f %13.5f %12.3f\n", "hex", hex_options.map_resolution,
              h.position_rmse, h.position_max, h.angle_rmse, h.ms_per_scan);
  std::printf("%-8s %10.4f %14.4f %12.4f %13.5f %12.3f\n", "square", square_options.map_resolution,
              s.position_rmse, s.position_max, s.angle_rmse, s.ms_per_scan);
  std::printf("(hex cell = centre spacing d; square side at equal cell area; square/hex position "
              "RMSE ratio %.2f)\n",
              s.position_rmse / h.position_rmse);

  const HexGrid& finest = hex.hex_maps()->level(0);
  const io::OccupancyRaster raster =
      io::Rasterize(finest, io::EqualAreaResolution(finest.lattice()));
  std::string error = io::SaveMapServerMap(raster, args.out + "/map");
  if (error.empty()) error = io::WritePng(args.out + "/map.png", ToImage(raster));
  // The hex map drawn as hexagons, with the true path (green) under the estimated one (red).
  io::ImageFrame frame;
  io::Image hex_image = io::RenderMap(finest, io::MapImageOptions(), &frame);
  std::vector<Eigen::Vector2d> path;
  for (const Pose2& p : drive.truth) path.push_back(p.translation());
  io::DrawPolyline(frame, path, {40, 170, 60}, 3, &hex_image);
  if (error.empty()) error = io::WritePng(args.out + "/hex_map.png", hex_image);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  std::printf("\nwrote %s/map.pgm, map.yaml, map.png (square raster) and hex_map.png "
              "(hexagons, true path in green)\n",
              args.out.c_str());
  std::printf("RESULT position_rmse_m=%.5f angle_rmse_rad=%.6f scans=%d position_max_m=%.5f "
              "square_position_rmse_m=%.5f square_angle_rmse_rad=%.6f\n",
              h.position_rmse, h.angle_rmse, h.scans, h.position_max, s.position_rmse,
              s.angle_rmse);
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::Main(argc, argv); }
