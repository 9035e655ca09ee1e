#include "hex_slam/sim/scenario.h"

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/sim/path_file.h"
#include "hex_slam/sim/waypoint_path.h"

namespace hex_slam {
namespace sim {
namespace {

// The robotcraft maze bitmap as its stage world places it: 1 cm pixels, corner at the origin.
constexpr const char* kRobotcraftBitmap = "robotcraft_maze/540x540-90cm.png";
constexpr double kRobotcraftResolution = 0.01;
// Initial map storage: covers the largest world from any start inside it without growing.
constexpr double kInitialMapSide = 24.0;  // m
// Coarsest cell (m) in the simulated worlds: their 0.9 m corridors smear together in coarser ones.
constexpr double kMaxCoarseCell = 0.5;

double Radians(double degrees) { return degrees * M_PI / 180.0; }

}  // namespace

std::string ScenarioSpec::Name() const {
  std::ostringstream s;
  s << map << "/" << cell_area << "/" << start_angle_deg << "/" << beams;
  return s.str();
}

std::string MakeScenario(const ScenarioSpec& spec, const ScenarioFiles& files,
                         const ScenarioConditions& conditions, Scenario* scenario) {
  Scenario result;
  result.spec = spec;
  std::string error, path_file;
  if (spec.map == "maze" || spec.map == "rooms") {
    error = LoadImageWorld(files.worlds_dir + "/" + spec.map + ".yaml", ImageWorldOptions(),
                           &result.image);
    path_file = files.worlds_dir + "/" + spec.map + "_path.yaml";
  } else if (spec.map == "robotcraft") {
    error = LoadBitmapWorld(files.data_dir + "/" + kRobotcraftBitmap, kRobotcraftResolution,
                            Eigen::Vector2d::Zero(), &result.image);
    path_file = files.worlds_dir + "/robotcraft_maze_path.yaml";
  } else {
    return "unknown map '" + spec.map + "' (maze, rooms or robotcraft)";
  }
  if (!error.empty()) return error;
  if (!(spec.cell_area > 0.0) || spec.beams < 3) return spec.Name() + ": bad cell area or beams";
  WaypointPath path;
  error = ReadWaypointPath(path_file, &path);
  if (!error.empty()) return error;

  PathMotion motion;
  motion.linear_speed = conditions.linear_speed;
  motion.angular_speed = conditions.angular_speed;
  motion.rate = conditions.scan_rate;
  const std::vector<Pose2> drive = SampleWaypointPath(path.waypoints, path.start_heading, motion);
  const Eigen::Vector2d start = path.waypoints.front();
  result.map_frame =
      Pose2(start.x(), start.y(), path.start_heading + Radians(spec.start_angle_deg));
  const Pose2 to_map = result.map_frame.inverse();
  for (const Pose2& p : drive) {
    Pose2 q = to_map * p;
    q.theta = NormalizeAngle(q.theta);
    result.truth.push_back(q);
  }
  result.scan_period = 1.0 / conditions.scan_rate;
  result.lidar.beams = spec.beams;
  result.lidar.field_of_view = 2.0 * M_PI;
  result.lidar.range_min = conditions.range_min;
  result.lidar.range_max = conditions.range_max;
  result.lidar.range_noise_stddev = conditions.range_noise;
  result.lidar.max_range_ghosts = conditions.max_range_ghosts;
  result.lidar.max_range_ghost_margin = conditions.max_range_ghost_margin;
  *scenario = std::move(result);
  return "";
}

SlamOptions ScenarioSlamOptions(const ScenarioSpec& spec, const std::string& lattice) {
  SlamOptions options;
  options.lattice = lattice;
  options.map_resolution =
      lattice == "hex" ? HexLattice::SpacingForArea(spec.cell_area) : std::sqrt(spec.cell_area);
  options.map_size = static_cast<int>(std::ceil(kInitialMapSide / options.map_resolution));
  options.map_max_coarse_resolution = kMaxCoarseCell;
  return options;
}

std::vector<PaperRow> PaperTable1() {
  // Duszak 2022, Table 1: test, parameters, position (hex, hector), angle (hex, hector).
  return {
      {1, {"maze", 0.01, 0.0, 1000}, 2.4e-2, 6.1e-2, 1.8e-4, 1.3e-4},
      {2, {"rooms", 0.01, 0.0, 1000}, 5.8e-2, 6.3e-2, 8.0e-5, 6.9e-5},
      {3, {"maze", 0.04, 0.0, 1000}, 5.01e-2, 1.4e-1, 1.7e-4, 3.4e-4},
      {4, {"maze", 0.01, 45.0, 1000}, 2.3e-2, 6.0e-2, 2.4e-4, 2.6e-4},
      {5, {"maze", 0.01, 60.0, 1000}, 1.5e-2, 4.1e-2, 1.7e-4, 4.2e-4},
      {6, {"maze", 0.01, 0.0, 360}, 2.4e-2, 5.3e-2, 2.0e-4, 1.2e-4},
  };
}

std::string DataDirectory(const std::string& source_dir) {
  const char* env = std::getenv("HEX_SLAM_DATA_DIR");
  if (env && *env) return env;
  return source_dir + "/../shared/data";
}

}  // namespace sim
}  // namespace hex_slam
