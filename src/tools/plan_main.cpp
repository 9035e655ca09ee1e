// hex_slam_plan: the shortest path on a saved hex map (a .hexmap from save_map or
// hex_slam_offline), without ROS. Prints the plan and ends with one RESULT line; --out draws it
// on the map's cells. Exit status 0 with a path, 1 without one, 2 on a usage or file error.
#include <chrono>
#include <cstdio>
#include <string>

#include "hex_slam/planning/hex_planner.h"
#include "hex_slam/io/hex_map_file.h"
#include "hex_slam/io/image_io.h"
#include "hex_slam/io/map_image.h"
#include "hex_slam/logs/offline/tool_arguments.h"
#include "tool_main.h"

namespace hex_slam {
namespace {

constexpr io::Rgb kPathColour = {220, 40, 40};
constexpr io::Rgb kStartColour = {40, 170, 60};
constexpr io::Rgb kGoalColour = {40, 90, 220};
constexpr int kPathThickness = 2;
constexpr int kEndRadius = 5;

struct Args {
  std::string map;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  bool have_start = false, have_goal = false;
  HexPlannerOptions planner;
  std::string out;
};

void Usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s --map FILE.hexmap --start x,y --goal x,y [--robot-radius M]\n"
               "          [--goal-tolerance M] [--allow-unknown] [--no-smoothing] [--out FILE.png]\n"
               "  A* over the finest level's hexagons (six equal steps per cell), keeping cell\n"
               "  centres farther than --robot-radius (default 0.2 m) from obstacles'.\n"
               "  The path is pulled taut unless --no-smoothing.\n"
               "  Ends with: RESULT found=0|1 length_m=... cell_path_length_m=... cells=...\n"
               "  waypoints=... expansions=... ms=...\n",
               argv0);
}

bool Parse(int argc, char** argv, Args* args, std::string* error) {
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (key == "--help" || key == "-h") return false;
    if (key == "--allow-unknown") {
      args->planner.allow_unknown = true;
      continue;
    }
    if (key == "--no-smoothing") {
      args->planner.smooth = false;
      continue;
    }
    if (i + 1 >= argc) {
      *error = key + " needs a value";
      return false;
    }
    const std::string value = argv[++i];
    if (value.empty()) {
      *error = key + " needs a value, got an empty one";
      return false;
    }
    bool ok = true;
    if (key == "--map") {
      args->map = value;
    } else if (key == "--start") {
      ok = args->have_start = logs::ParsePoint(value, &args->start);
    } else if (key == "--goal") {
      ok = args->have_goal = logs::ParsePoint(value, &args->goal);
    } else if (key == "--robot-radius") {
      ok = logs::ParseNumber(value, &args->planner.robot_radius);
    } else if (key == "--goal-tolerance") {
      ok = logs::ParseNumber(value, &args->planner.goal_tolerance);
    } else if (key == "--out") {
      args->out = value;
    } else {
      *error = "unknown option " + key;
      return false;
    }
    if (!ok) {
      *error = "bad value for " + key + ": '" + value + "'";
      return false;
    }
  }
  if (args->map.empty() || !args->have_start || !args->have_goal) {
    *error = "--map, --start and --goal are required";
    return false;
  }
  const std::vector<std::string> invalid = args->planner.Validate();
  if (!invalid.empty()) {
    *error = invalid.front();
    return false;
  }
  return true;
}

// The finest level of a hex map file as a grid.
std::string LoadFinestLevel(const std::string& path, std::optional<GridMap<HexLattice>>* grid) {
  io::HexMapData data;
  const std::string error = io::ReadHexMapFile(path, &data);
  if (!error.empty()) return error;
  if (data.lattice != "hex") return path + ": a " + data.lattice + " map; planning needs hexagons";
  const io::HexMapLevel& finest = data.levels.front();
  grid->emplace(HexLattice(data.spacing), data.model, GridGrowthPolicy(),
                Eigen::AlignedBox2d(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()));
  (*grid)->Assign(finest.rect, finest.log_odds);
  return "";
}

std::string Draw(const GridMap<HexLattice>& grid, const HexPlan& plan, const Args& args) {
  io::ImageFrame frame;
  io::Image image = io::RenderMap(grid, io::MapImageOptions(), &frame);
  if (plan.found) io::DrawPolyline(frame, plan.waypoints, kPathColour, kPathThickness, &image);
  io::DrawDisc(frame, args.start, kEndRadius, kStartColour, &image);
  io::DrawDisc(frame, args.goal, kEndRadius, kGoalColour, &image);
  return io::WritePng(args.out, image);
}

int Main(int argc, char** argv) {
  Args args;
  std::string usage_error;
  if (!Parse(argc, argv, &args, &usage_error)) {
    if (!usage_error.empty()) std::fprintf(stderr, "error: %s\n", usage_error.c_str());
    Usage(argv[0]);
    return 2;
  }
  std::optional<GridMap<HexLattice>> grid;
  const std::string error = LoadFinestLevel(args.map, &grid);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 2;
  }
  const auto begin = std::chrono::steady_clock::now();
  const HexPlan plan = PlanHexPath(grid->log_odds_grid(), args.start, args.goal, args.planner);
  const double ms =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  if (plan.found) {
    std::printf("path: %zu cells, %.3f m pulled taut (%.3f m along the cells, straight line "
                "%.3f m), %zu waypoints, %ld cells expanded, %.2f ms\n",
                plan.cells.size(), plan.length, plan.cell_path_length,
                (args.goal - args.start).norm(), plan.waypoints.size(),
                static_cast<long>(plan.expansions), ms);
  } else {
    std::printf("no path: %s\n", plan.message.c_str());
  }
  if (!args.out.empty()) {
    const std::string draw_error = Draw(*grid, plan, args);
    if (!draw_error.empty()) {
      std::fprintf(stderr, "error: %s\n", draw_error.c_str());
      return 2;
    }
    std::printf("wrote %s\n", args.out.c_str());
  }
  std::printf("RESULT found=%d length_m=%.4f cell_path_length_m=%.4f cells=%zu waypoints=%zu "
              "expansions=%ld ms=%.3f\n",
              plan.found ? 1 : 0, plan.length, plan.cell_path_length, plan.cells.size(),
              plan.waypoints.size(), static_cast<long>(plan.expansions), ms);
  return plan.found ? 0 : 1;
}

}  // namespace
}  // namespace hex_slam

int main(int argc, char** argv) { return hex_slam::RunToolMain(hex_slam::Main, argc, argv); }
