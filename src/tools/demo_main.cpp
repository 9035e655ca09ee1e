// hex_slam_demo: the paper's experiment in one command, without ROS. By default it drives the
// maze of the paper's Table 1, row 1 (0.01 m² cells, walls at 0° to the map's axes, 1000 beams,
// no odometry; the scenario code hex_slam_bench runs), maps it with hex_slam (hex lattice) and
// with hector_mapping's method (square lattice of equal cell area, no sub-cell offsets) on the
// same scans, prints both errors against ground truth and their ratio, and writes the hex map as
// map_server PGM+YAML, a PNG of that raster, a PNG of the hexagons, and the paths drawn on the
// map. `--scenario room` runs the older loop through a 10 m x 8 m room instead.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <optional>
#include <random>
#include <string>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/io/image_io.h"
#include "hex_slam/io/map_image.h"
#include "hex_slam/io/map_server_io.h"
#include "hex_slam/io/occupancy_raster.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/sim/scenario.h"
#include "hex_slam/sim/scenario_run.h"
#include "hex_slam/mapping/slam.h"
#include "command_line.h"
#include "tool_main.h"

#ifndef HEX_SLAM_SOURCE_DIR
#define HEX_SLAM_SOURCE_DIR "."
#endif

namespace hex_slam {
namespace {

// The paper's row 1: the maze, 0.01 m² cells, 0°, 1000 beams.
constexpr double kMazeCellArea = 0.01;         // m²
constexpr int kMazeBeams = 1000;
// The room drive's historical defaults: 0.05 m hexes, a 360-beam lidar.
constexpr double kRoomResolution = 0.05;       // m, hex centre spacing
constexpr int kRoomBeams = 360;
// --beams and --resolution when not given: the scenario's, chosen once it is known.
constexpr int kScenarioBeams = 0;
constexpr double kScenarioResolution = 0.0;
constexpr int kMinBeams = 3;  // the simulated lidar's least

constexpr io::Rgb kTruthColour = {40, 170, 60};
constexpr io::Rgb kHexColour = {220, 40, 40};
constexpr io::Rgb kSquareColour = {40, 90, 220};
constexpr double kTrajectoryPixelsPerMetre = 150.0;
constexpr int kTruthThickness = 5;
constexpr int kEstimateThickness = 2;

struct Args {
  std::string scenario = "maze";
  std::string out = "out/demo";
  std::string worlds = std::string(HEX_SLAM_SOURCE_DIR) + "/worlds";
  int beams = kScenarioBeams;
  double resolution = kScenarioResolution;  // hex centre spacing, m
  double noise = 0.01;  // m
  unsigned seed = 1;
};

// The command line; the checks that span options come after parsing (CheckArgs).
void Declare(CLI::App* app, Args* args) {
  app->description(
      "The paper's experiment without ROS: maps one simulated drive with hex_slam (hexagons) and "
      "with hector_mapping's method (no sub-cell offsets) on squares of side sqrt(sqrt(3)/2) D, "
      "at equal cell area, and prints both errors against the truth.");
  app->footer(
      "Ends with: RESULT position_rmse_m=... angle_rmse_rad=... scans=... position_max_m=... "
      "square_position_rmse_m=... square_angle_rmse_rad=... square_over_hex=... (the first four "
      "hex_slam's)");
  app->add_option("--scenario", args->scenario,
                  "maze (default): the paper's Table 1 row 1 - worlds/maze, 0.01 m2 cells (hex "
                  "centre spacing D = 0.1075 m), 0 deg, 1000 beams over 360 deg at 10 Hz, no "
                  "odometry; room: a loop through a 10 m x 8 m room, D = 0.05 m, 360 beams")
      ->check(cli::NonEmpty());
  app->add_option("--out", args->out,
                  "writes map.pgm + map.yaml, map.png, hex_map.png and trajectory.png (default "
                  "out/demo)")
      ->check(cli::NonEmpty());
  app->add_option("--beams", args->beams, "beams per scan (default, or 0: the scenario's)")
      ->check(CLI::Range(0L, kMaxScanReadings));
  cli::AddNumber(app, "--resolution", &args->resolution,
                 "hex centre spacing D, m (default, or 0: the scenario's)", 0.0);
  cli::AddNumber(app, "--noise", &args->noise,
                 "lidar range noise, standard deviation in m (default 0.01)", 0.0);
  app->add_option("--seed", args->seed, "the lidar noise's random seed (default 1)");
  app->add_option("--worlds", args->worlds, "the folder of maze.yaml (default: the source tree's)")
      ->check(cli::NonEmpty());
}

// Empty, or what is wrong with the options taken together.
std::string CheckArgs(const Args& args) {
  if (args.scenario != "maze" && args.scenario != "room") {
    return "--scenario takes maze or room, got '" + args.scenario + "'";
  }
  if (args.beams != kScenarioBeams && args.beams < kMinBeams) {
    return "--beams: a scan needs at least " + std::to_string(kMinBeams) + " beams, got " +
           std::to_string(args.beams);
  }
  return "";
}

void UseScenarioDefaults(Args* args) {
  const bool maze = args->scenario == "maze";
  if (args->beams == kScenarioBeams) args->beams = maze ? kMazeBeams : kRoomBeams;
  if (args->resolution == kScenarioResolution) {
    args->resolution = maze ? HexLattice::SpacingForArea(kMazeCellArea) : kRoomResolution;
  }
}

// What both lattices are run on: the scans, the truth, and how the drive was described.
struct Drive {
  sim::RecordedDrive recorded;
  std::string description;
};

std::string MakeMazeDrive(const Args& args, Drive* drive) {
  sim::ScenarioSpec spec;
  spec.map = "maze";
  spec.cell_area = HexLattice(args.resolution).cell_area();
  spec.beams = args.beams;
  sim::ScenarioConditions conditions;
  conditions.range_noise = args.noise;
  sim::Scenario scenario;
  const std::string error =
      sim::MakeScenario(spec, sim::ScenarioFiles{args.worlds, ""}, conditions, &scenario);
  if (!error.empty()) return error + " (give the worlds folder with --worlds)";
  drive->recorded = sim::RecordDrive(scenario, args.seed);
  char text[256];
  std::snprintf(text, sizeof(text),
                "the paper's maze (%s: %.2f m2 cells, %d beams, noise %.3f m, no odometry)",
                spec.Name().c_str(), spec.cell_area, spec.beams, args.noise);
  drive->description = text;
  return "";
}

void MakeRoomDrive(const Args& args, Drive* drive) {
  const sim::RoomDrive room = sim::MakeRoomDrive(args.beams, args.noise);
  std::mt19937_64 rng(args.seed);
  drive->recorded.truth = room.truth;
  for (std::size_t i = 0; i < room.truth.size(); ++i) {
    drive->recorded.scans.push_back(
        sim::SimulateScan(room.world, room.truth[i], room.lidar, room.scan_period * i, &rng));
  }
  char text[256];
  std::snprintf(text, sizeof(text),
                "a loop through a 10 m x 8 m room (%d beams, noise %.3f m, no odometry)",
                args.beams, args.noise);
  drive->description = text;
}

// hex_slam as shipped on hexagons of centre spacing `resolution`; hector_mapping's method on
// squares of the same area.
SlamOptions LatticeOptions(const std::string& lattice, double resolution) {
  SlamOptions options;
  options.lattice = lattice;
  options.map_resolution = resolution;
  if (lattice == "square") {
    options.map_resolution = std::sqrt(HexLattice(resolution).cell_area());
    options.matcher.subcell_offsets = false;
  }
  return options;
}

struct LatticeRun {
  SlamOptions options;
  sim::SlamRun run;
  sim::TrajectoryError error;
  double ms_per_scan = 0.0;
};

LatticeRun RunLattice(const Drive& drive, const SlamOptions& options, Slam* slam) {
  LatticeRun result;
  result.options = options;
  result.run = sim::RunSlam(drive.recorded, /*use_odometry=*/false, slam);
  result.error = sim::CompareTrajectories(result.run.poses, drive.recorded.truth);
  const double seconds =
      std::accumulate(result.run.scan_seconds.begin(), result.run.scan_seconds.end(), 0.0);
  result.ms_per_scan = 1e3 * seconds / std::max<std::size_t>(1, result.run.scan_seconds.size());
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

std::vector<Eigen::Vector2d> Positions(const std::vector<Pose2>& poses) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(poses.size());
  for (const Pose2& p : poses) points.push_back(p.translation());
  return points;
}

// map.{pgm,yaml,png}: the hex map rasterised at equal cell area; hex_map.png: its cells;
// trajectory.png: the truth (green, wide) under hex_slam's path (red) and hector's method's
// (blue).
std::string WriteOutputs(const std::string& dir, const HexGrid& finest, const Drive& drive,
                         const LatticeRun& hex, const LatticeRun& square) {
  const io::OccupancyRaster raster =
      io::Rasterize(finest.log_odds_grid(), io::MapResolution(finest.lattice()));
  std::string error = io::SaveMapServerMap(raster, dir + "/map");
  if (error.empty()) error = io::WritePng(dir + "/map.png", ToImage(raster));
  io::ImageFrame frame;
  if (error.empty()) {
    error = io::WritePng(dir + "/hex_map.png", io::RenderMap(finest, io::MapImageOptions(), &frame));
  }
  if (!error.empty()) return error;
  io::MapImageOptions plain;
  plain.cell_outlines = false;
  plain.pixels_per_metre = kTrajectoryPixelsPerMetre;
  io::Image picture = io::RenderMap(finest, plain, &frame);
  io::DrawPolyline(frame, Positions(drive.recorded.truth), kTruthColour, kTruthThickness, &picture);
  io::DrawPolyline(frame, Positions(square.run.poses), kSquareColour, kEstimateThickness, &picture);
  io::DrawPolyline(frame, Positions(hex.run.poses), kHexColour, kEstimateThickness, &picture);
  return io::WritePng(dir + "/trajectory.png", picture);
}

int Main(int argc, char** argv) {
  Args args;
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_demo", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args] { return CheckArgs(args); })) {
    return *status;
  }
  UseScenarioDefaults(&args);
  std::error_code dir_error;
  std::filesystem::create_directories(args.out, dir_error);
  if (dir_error) {
    std::fprintf(stderr, "error: cannot create %s: %s\n", args.out.c_str(),
                 dir_error.message().c_str());
    return 1;
  }
  Drive drive;
  if (args.scenario == "maze") {
    const std::string error = MakeMazeDrive(args, &drive);
    if (!error.empty()) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return 1;
    }
  } else {
    MakeRoomDrive(args, &drive);
  }
  std::printf("hex_slam demo: %zu scans along %s\n", drive.recorded.truth.size(),
              drive.description.c_str());

  const SlamOptions hex_options = LatticeOptions("hex", args.resolution);
  const SlamOptions square_options = LatticeOptions("square", args.resolution);
  Slam hex_slam(hex_options), square_slam(square_options);
  const LatticeRun hex = RunLattice(drive, hex_options, &hex_slam);
  const LatticeRun square = RunLattice(drive, square_options, &square_slam);
  const double ratio = square.error.position_rmse / hex.error.position_rmse;

  std::printf("\n%-28s %8s %11s %10s %11s %8s\n", "method", "cell_m", "pos_rmse_m", "pos_max_m",
              "angle_rmse", "ms/scan");
  const auto row = [](const char* name, const LatticeRun& r) {
    std::printf("%-28s %8.4f %11.4f %10.4f %11.5f %8.3f\n", name, r.options.map_resolution,
                r.error.position_rmse, r.error.position_max, r.error.angle_rmse, r.ms_per_scan);
  };
  row("hex_slam (hex)", hex);
  row("hector's method (square)", square);
  std::printf("square/hex position RMSE: %.2f (hex cell = centre spacing d; square side at equal "
              "cell area)\n",
              ratio);

  const std::string error =
      WriteOutputs(args.out, hex_slam.hex_maps()->level(0), drive, hex, square);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }
  std::printf("\nwrote %s/map.pgm, map.yaml, map.png (square raster), hex_map.png (hexagons) and "
              "trajectory.png (truth green, hex red, square blue)\n",
              args.out.c_str());
  std::printf("RESULT position_rmse_m=%.5f angle_rmse_rad=%.6f scans=%d position_max_m=%.5f "
              "square_position_rmse_m=%.5f square_angle_rmse_rad=%.6f square_over_hex=%.3f\n",
              hex.error.position_rmse, hex.error.angle_rmse, hex.error.poses,
              hex.error.position_max, square.error.position_rmse, square.error.angle_rmse, ratio);
  return 0;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
