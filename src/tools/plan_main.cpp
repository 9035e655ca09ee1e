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
#include "command_line.h"
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
  HexPlannerOptions planner;
  std::string out;
};

void Declare(CLI::App* app, Args* args) {
  app->description(
      "The shortest path on a saved hex map (a .hexmap from save_map or hex_slam_offline): A* "
      "over the finest level's hexagons (six equal steps per cell), keeping cell centres farther "
      "than --robot-radius from obstacles'. Exit status 0 with a path, 1 without one, 2 on a "
      "usage or file error.");
  app->footer(
      "Ends with: RESULT found=0|1 length_m=... cell_path_length_m=... cells=... waypoints=... "
      "expansions=... ms=...");
  app->add_option("--map", args->map, "the .hexmap")->required()->check(cli::NonEmpty());
  cli::AddPoint(app, "--start", &args->start, "where the path starts (m)")->required();
  cli::AddPoint(app, "--goal", &args->goal, "where it ends (m)")->required();
  cli::AddNumber(app, "--robot-radius", &args->planner.robot_radius,
                 "the clearance (m) kept from obstacles (default 0.2)");
  cli::AddNumber(app, "--goal-tolerance", &args->planner.goal_tolerance,
                 "how near the goal (m) the path may end");
  app->add_flag("--allow-unknown", args->planner.allow_unknown, "plans through unknown cells");
  app->add_flag_callback("--no-smoothing", [args] { args->planner.smooth = false; },
                         "keeps the path on the cells instead of pulling it taut");
  app->add_option("--out", args->out, "draws the path on the map's cells (PNG)")
      ->check(cli::NonEmpty());
}

// Empty, or the planner options' first fault.
std::string CheckArgs(const Args& args) {
  const std::vector<std::string> invalid = args.planner.Validate();
  return invalid.empty() ? "" : invalid.front();
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
  if (const std::optional<int> status = cli::ParseCommandLine(
          "hex_slam_plan", argc, argv, [&args](CLI::App* app) { Declare(app, &args); },
          [&args] { return CheckArgs(args); })) {
    return *status;
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
