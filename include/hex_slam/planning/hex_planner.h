// Shortest paths on the hex map: A* over the cells, each step to one of the six neighbours, all
// of them one spacing away. A square grid must choose between 4 neighbours (staircase paths) and
// 8 with two step lengths; here every step is the same, so the step count is the path length
// and the hex distance is an exact lower bound of it (an admissible, consistent heuristic).
//
// A cell can be entered when it is known free (or unknown, with allow_unknown) and its centre is
// farther than robot_radius from the centre of every occupied cell, and (keep_clear_of_unknown)
// of every unknown cell at the edge of the known map: a path along a lone beam's trace through
// unexplored space, or skirting it, could meet what no scan has seen. A robot that starts closer
// than that (parked by a wall) may leave through such cells, each farther from the obstacles
// than the one before; no path comes back into them.
#ifndef HEX_SLAM_PLANNING_HEX_PLANNER_H_
#define HEX_SLAM_PLANNING_HEX_PLANNER_H_

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/map/log_odds_grid.h"

namespace hex_slam {

struct HexPlannerOptions {
  double robot_radius = 0.2;            // m: no path cell's centre comes closer to an obstacle's
  double occupied_probability = 0.65;   // a cell at or above this is an obstacle
  bool allow_unknown = false;           // plan through cells never observed
  bool keep_clear_of_unknown = true;    // unknown cells next to known ones count as obstacles
                                        // for robot_radius (not with allow_unknown)
  double goal_tolerance = 0.0;          // m: an unreachable goal may move this far to a free cell
  // Pull the cell path taut: drop every waypoint the previous kept one sees past, where the
  // straight segment crosses (exact ray traversal) only cells the path may use.
  bool smooth = true;
  std::int64_t max_expansions = std::int64_t{1} << 24;  // cells expanded before giving up
  // Cells visited to inflate the obstacles by robot_radius (obstacle and unknown-edge cells times
  // the cells of the radius's disc), or to search goal_tolerance's disc. More is refused with a
  // message: a robot_radius of 10 m on the Intel map, or 0.2 m on cells of 0.1 mm, took minutes.
  // The default is ~0.5 s of inflation; the Intel map (24,817 such cells at 0.05 m) takes 36
  // million steps with robot_radius 1 m, and is refused from 2 m on.
  std::int64_t max_inflation_steps = std::int64_t{1} << 27;

  // Empty when valid; otherwise one message per bad field.
  std::vector<std::string> Validate() const;
};

// What a cell is to the planner.
enum class Traversability : std::uint8_t { kFree, kUnknown, kInflated, kOccupied };

struct PlannerCells {
  std::vector<Traversability> kind;  // per storage cell of the map (row-major over its rect)
  std::vector<float> clearance;      // m from an inflated cell's centre to the nearest obstacle's
                                     // (or unknown edge cell's)
  // Empty when classified; otherwise why not (the inflation exceeds max_inflation_steps), and
  // `kind` and `clearance` are empty.
  std::string refused;
};

// The map the planner reads: the log-odds of the hex cells (a GridMap's log_odds_grid(), or the
// node's copy of it).
using HexPlannerMap = LogOddsGrid<HexLattice>;

PlannerCells ClassifyCells(const HexPlannerMap& map, const HexPlannerOptions& options);

// Whether a path may step from cell `from` to its neighbour `to` (storage offsets).
bool MayStep(const PlannerCells& cells, std::size_t from, std::size_t to, bool allow_unknown);

struct HexPlan {
  bool found = false;
  std::string message;                    // why not, when not found
  std::vector<HexCell> cells;             // start cell to goal cell, neighbours in turn
  // The start point, the cells' centres (only the corners when smoothed), the goal point.
  std::vector<Eigen::Vector2d> waypoints;
  double length = 0.0;                    // m, along the waypoints
  double cell_path_length = 0.0;          // m, along every cell's centre (before smoothing)
  std::int64_t expansions = 0;
};

// The shortest path from `start` to `goal` (world, m). The start cell may lie within
// robot_radius of an obstacle (the robot is there: the path leads out), not in one.
HexPlan PlanHexPath(const HexPlannerMap& map, const Eigen::Vector2d& start,
                    const Eigen::Vector2d& goal, const HexPlannerOptions& options);

// The polyline `points` with points added so none is more than `step` (m) from the next, for
// followers that expect a dense path (as move_base's global planners give).
std::vector<Eigen::Vector2d> ResamplePath(const std::vector<Eigen::Vector2d>& points, double step);

}  // namespace hex_slam

#endif  // HEX_SLAM_PLANNING_HEX_PLANNER_H_
