#include "hex_slam/planning/hex_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <sstream>

#include "hex_slam/geometry/ray_traversal.h"

namespace hex_slam {
namespace {

constexpr std::int64_t kNoParent = -1;
// Radii past this (robot, goal tolerance) are refused: the discs they span are searched cell by
// cell.
constexpr double kMaxRadius = 10.0;  // m

// The axial offsets DiscOffsets(radius) looks at: a square of them around the disc.
double DiscSearchCells(const HexLattice& lattice, double radius) {
  const double side = 2.0 * std::floor(radius / lattice.cube_scale()) + 1.0;
  return side * side;
}

// Empty when searching `radius`'s disc fits max_inflation_steps; else why not.
std::string OverBudget(const HexLattice& lattice, double radius, const char* what,
                       const HexPlannerOptions& options) {
  const double steps = DiscSearchCells(lattice, radius);
  if (steps <= static_cast<double>(options.max_inflation_steps)) return "";
  std::ostringstream s;
  s << what << " " << radius << " m on cells " << lattice.spacing() << " m apart takes " << steps
    << " steps, more than max_inflation_steps (" << options.max_inflation_steps << ")";
  return s.str();
}

// The axial offsets of every cell whose centre lies within `radius` of a cell's centre.
std::vector<HexCell> DiscOffsets(const HexLattice& lattice, double radius) {
  // A cell k steps away is at least k·w from the centre (w = sqrt(3)/2 · d), so k <= radius / w.
  const int reach = static_cast<int>(std::floor(radius / lattice.cube_scale()));
  const Eigen::Vector2d origin = lattice.CentreOf(HexCell{0, 0});
  std::vector<HexCell> offsets;
  for (int a = -reach; a <= reach; ++a) {
    for (int b = -reach; b <= reach; ++b) {
      const HexCell c{a, b};
      if (HexDistance(c, HexCell{0, 0}) > reach) continue;
      if ((lattice.CentreOf(c) - origin).norm() <= radius) offsets.push_back(c);
    }
  }
  return offsets;
}

bool Enterable(Traversability t, bool allow_unknown) {
  return t == Traversability::kFree || (allow_unknown && t == Traversability::kUnknown);
}

constexpr float kNoClearance = std::numeric_limits<float>::infinity();

// The enterable cell nearest to `point` within `tolerance` (m), if any.
bool NearestEnterable(const HexPlannerMap& map, const PlannerCells& cells,
                      const Eigen::Vector2d& point, const HexPlannerOptions& options,
                      HexCell* found) {
  const HexLattice& lattice = map.lattice();
  const HexCell centre = lattice.CellOf(point);
  double best = std::numeric_limits<double>::infinity();
  // PlanHexPath checked the disc against the budget.
  for (const HexCell& d : DiscOffsets(lattice, options.goal_tolerance + lattice.spacing())) {
    const HexCell c{centre.a + d.a, centre.b + d.b};
    const GridIndex index = HexLattice::ToIndex(c);
    if (!map.rect().Contains(index)) continue;
    if (!Enterable(cells.kind[map.rect().Offset(index)], options.allow_unknown)) continue;
    const double distance = (lattice.CentreOf(c) - point).norm();
    if (distance <= options.goal_tolerance && distance < best) {
      best = distance;
      *found = c;
    }
  }
  return std::isfinite(best);
}

struct Open {
  double f;
  double g;
  std::int64_t offset;
  // std::priority_queue pops the largest: the smallest f first, and among equal f the one
  // nearest the goal (largest g), which keeps the search from fanning out over ties.
  bool operator<(const Open& o) const { return f > o.f || (f == o.f && g < o.g); }
};

double PathLength(const std::vector<Eigen::Vector2d>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

// Whether the segment a→b crosses only cells a path may use: enterable ones, or the path's own
// (a start inside the inflated band leaves it along its cells).
bool Clear(const HexPlannerMap& map, const PlannerCells& cells,
           const std::vector<bool>& on_path, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
           bool allow_unknown, std::vector<HexCell>* crossed) {
  TraceRay(map.lattice(), a, b, crossed);
  crossed->push_back(map.lattice().CellOf(b));
  for (const HexCell& c : *crossed) {
    const GridIndex index = HexLattice::ToIndex(c);
    if (!map.rect().Contains(index)) return false;
    const std::size_t o = map.rect().Offset(index);
    if (!on_path[o] && !Enterable(cells.kind[o], allow_unknown)) return false;
  }
  return true;
}

// Greedy string pulling: from each kept waypoint, on to the farthest later one it sees.
std::vector<Eigen::Vector2d> PullTaut(const HexPlannerMap& map, const PlannerCells& cells,
                                      const HexPlan& plan, const HexPlannerOptions& options) {
  std::vector<bool> on_path(map.rect().size(), false);
  for (const HexCell& c : plan.cells) on_path[map.rect().Offset(HexLattice::ToIndex(c))] = true;
  const std::vector<Eigen::Vector2d>& w = plan.waypoints;
  std::vector<Eigen::Vector2d> taut = {w.front()};
  std::vector<HexCell> crossed;
  std::size_t at = 0;
  while (at + 1 < w.size()) {
    std::size_t next = at + 1;
    for (std::size_t j = at + 2; j < w.size(); ++j) {
      if (!Clear(map, cells, on_path, w[at], w[j], options.allow_unknown, &crossed)) break;
      next = j;
    }
    taut.push_back(w[next]);
    at = next;
  }
  return taut;
}

}  // namespace

std::vector<std::string> HexPlannerOptions::Validate() const {
  std::vector<std::string> errors;
  if (!(robot_radius >= 0.0 && robot_radius <= kMaxRadius)) {
    errors.push_back("planner robot_radius must be in [0, 10] m");
  }
  if (!(occupied_probability > 0.5 && occupied_probability <= 1.0)) {
    errors.push_back("planner occupied_probability must be in (0.5, 1]");
  }
  if (!(goal_tolerance >= 0.0 && goal_tolerance <= kMaxRadius)) {
    errors.push_back("planner goal_tolerance must be in [0, 10] m");
  }
  if (max_expansions < 1) errors.push_back("planner max_expansions must be >= 1");
  if (max_inflation_steps < 1) errors.push_back("planner max_inflation_steps must be >= 1");
  return errors;
}

PlannerCells ClassifyCells(const HexPlannerMap& map, const HexPlannerOptions& options) {
  const GridRect& rect = map.rect();
  const float* log_odds = map.data();
  PlannerCells cells;
  const HexLattice& lattice = map.lattice();
  cells.refused = OverBudget(lattice, options.robot_radius, "robot_radius", options);
  if (!cells.refused.empty()) return cells;
  cells.kind.assign(rect.size(), Traversability::kFree);
  cells.clearance.assign(rect.size(), kNoClearance);
  std::vector<std::size_t> occupied;
  for (std::size_t i = 0; i < rect.size(); ++i) {
    if (log_odds[i] != 0.0f &&
        OccupancyModel::Probability(log_odds[i]) >= options.occupied_probability) {
      occupied.push_back(i);
    } else if (log_odds[i] == 0.0f) {
      cells.kind[i] = Traversability::kUnknown;
    }
  }
  // The edge of the unknown: unknown cells with a known neighbour. Keeping clear of these keeps
  // clear of every unknown cell as well, up to a cell's width.
  std::vector<std::size_t> keep_clear = occupied;
  if (options.keep_clear_of_unknown && !options.allow_unknown) {
    for (std::size_t i = 0; i < rect.size(); ++i) {
      if (cells.kind[i] != Traversability::kUnknown) continue;
      const HexCell c = HexLattice::FromIndex(rect.IndexAt(i));
      for (int k = 0; k < 6; ++k) {
        const GridIndex n = HexLattice::ToIndex(HexCell{c.a + kHexNeighbourDa[k],
                                                        c.b + kHexNeighbourDb[k]});
        if (rect.Contains(n) && cells.kind[rect.Offset(n)] != Traversability::kUnknown) {
          keep_clear.push_back(i);
          break;
        }
      }
    }
  }
  // Counted before the disc is built: its cells number about pi r^2 over a cell's area.
  const double disc_cells =
      M_PI * options.robot_radius * options.robot_radius / lattice.cell_area() + 1.0;
  const double steps = static_cast<double>(keep_clear.size()) * disc_cells;
  if (steps > static_cast<double>(options.max_inflation_steps)) {
    std::ostringstream s;
    s << "inflating " << keep_clear.size() << " obstacle and unknown-edge cells by robot_radius "
      << options.robot_radius << " m (about " << std::round(disc_cells) << " cells each) takes "
      << "about " << steps << " steps, more than max_inflation_steps ("
      << options.max_inflation_steps << ")";
    PlannerCells refused;
    refused.refused = s.str();
    return refused;
  }
  const Eigen::Vector2d origin = lattice.CentreOf(HexCell{0, 0});
  const std::vector<HexCell> disc = DiscOffsets(lattice, options.robot_radius);
  std::vector<float> distance;
  for (const HexCell& d : disc) {
    distance.push_back(static_cast<float>((lattice.CentreOf(d) - origin).norm()));
  }
  for (const std::size_t i : keep_clear) {
    const HexCell c = HexLattice::FromIndex(rect.IndexAt(i));
    for (std::size_t k = 0; k < disc.size(); ++k) {
      const GridIndex index = HexLattice::ToIndex(HexCell{c.a + disc[k].a, c.b + disc[k].b});
      if (!rect.Contains(index)) continue;
      const std::size_t o = rect.Offset(index);
      // Unknown stays unknown when it is not entered anyway.
      if (cells.kind[o] == Traversability::kUnknown && !options.allow_unknown) continue;
      cells.kind[o] = Traversability::kInflated;
      cells.clearance[o] = std::min(cells.clearance[o], distance[k]);
    }
  }
  for (const std::size_t i : occupied) {
    cells.kind[i] = Traversability::kOccupied;
    cells.clearance[i] = 0.0f;
  }
  return cells;
}

bool MayStep(const PlannerCells& cells, std::size_t from, std::size_t to, bool allow_unknown) {
  if (Enterable(cells.kind[to], allow_unknown)) return true;
  // Out of the inflated band only: from a cell of it to one farther from the obstacles.
  return cells.kind[to] == Traversability::kInflated &&
         cells.kind[from] == Traversability::kInflated &&
         cells.clearance[to] > cells.clearance[from];
}

std::vector<Eigen::Vector2d> ResamplePath(const std::vector<Eigen::Vector2d>& points,
                                          double step) {
  std::vector<Eigen::Vector2d> dense;
  if (points.empty()) return dense;
  dense.push_back(points.front());
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Eigen::Vector2d delta = points[i] - points[i - 1];
    const int pieces = std::max(1, static_cast<int>(std::ceil(delta.norm() / step)));
    for (int k = 1; k <= pieces; ++k) dense.push_back(points[i - 1] + delta * (double(k) / pieces));
  }
  return dense;
}

HexPlan PlanHexPath(const HexPlannerMap& map, const Eigen::Vector2d& start,
                    const Eigen::Vector2d& goal, const HexPlannerOptions& options) {
  HexPlan plan;
  const std::vector<std::string> invalid = options.Validate();
  if (!invalid.empty()) {
    plan.message = invalid.front();
    return plan;
  }
  if (!start.allFinite() || !goal.allFinite()) {
    plan.message = "the start and the goal must be finite points";
    return plan;
  }
  const HexLattice& lattice = map.lattice();
  const GridRect& rect = map.rect();
  // Points far outside would overflow the integer cell indices: measured in metres first.
  const Eigen::AlignedBox2d extent = map.StorageExtent();
  if (extent.exteriorDistance(start) > lattice.spacing()) {
    plan.message = "the start lies outside the map";
    return plan;
  }
  if (extent.exteriorDistance(goal) > options.goal_tolerance + lattice.spacing()) {
    plan.message = "the goal lies outside the map";
    return plan;
  }
  const HexCell start_cell = lattice.CellOf(start);
  HexCell goal_cell = lattice.CellOf(goal);
  if (!rect.Contains(HexLattice::ToIndex(start_cell))) {
    plan.message = "the start lies outside the map";
    return plan;
  }
  plan.message =
      OverBudget(lattice, options.goal_tolerance + lattice.spacing(), "goal_tolerance", options);
  if (!plan.message.empty()) return plan;
  const PlannerCells cells = ClassifyCells(map, options);
  if (!cells.refused.empty()) {
    plan.message = cells.refused;
    return plan;
  }
  if (cells.kind[rect.Offset(HexLattice::ToIndex(start_cell))] == Traversability::kOccupied) {
    plan.message = "the start lies in an obstacle";
    return plan;
  }
  const GridIndex goal_index = HexLattice::ToIndex(goal_cell);
  if (!rect.Contains(goal_index) ||
      !Enterable(cells.kind[rect.Offset(goal_index)], options.allow_unknown)) {
    if (!NearestEnterable(map, cells, goal, options, &goal_cell)) {
      plan.message = "the goal lies outside the map, in or within robot_radius of an obstacle" +
                     std::string(options.allow_unknown ? "" : ", or in unknown space") +
                     " (nothing free within goal_tolerance)";
      return plan;
    }
  }

  const double step = lattice.spacing();
  std::vector<double> g(rect.size(), std::numeric_limits<double>::infinity());
  std::vector<std::int64_t> parent(rect.size(), kNoParent);
  std::priority_queue<Open> open;
  const std::int64_t start_offset = rect.Offset(HexLattice::ToIndex(start_cell));
  const std::int64_t goal_offset = rect.Offset(HexLattice::ToIndex(goal_cell));
  g[start_offset] = 0.0;
  open.push({step * HexDistance(start_cell, goal_cell), 0.0, start_offset});
  bool reached = start_offset == goal_offset;
  while (!open.empty() && !reached) {
    const Open top = open.top();
    open.pop();
    if (top.g > g[top.offset]) continue;  // a stale entry: the cell was reached cheaper since
    if (++plan.expansions > options.max_expansions) {
      plan.message = "gave up after max_expansions cells";
      return plan;
    }
    const HexCell cell = HexLattice::FromIndex(rect.IndexAt(top.offset));
    for (int k = 0; k < 6; ++k) {
      const HexCell next{cell.a + kHexNeighbourDa[k], cell.b + kHexNeighbourDb[k]};
      const GridIndex index = HexLattice::ToIndex(next);
      if (!rect.Contains(index)) continue;
      const std::int64_t offset = rect.Offset(index);
      if (!MayStep(cells, top.offset, offset, options.allow_unknown)) continue;
      const double cost = top.g + step;
      if (cost >= g[offset]) continue;
      g[offset] = cost;
      parent[offset] = top.offset;
      if (offset == goal_offset) {
        reached = true;
        break;
      }
      open.push({cost + step * HexDistance(next, goal_cell), cost, offset});
    }
  }
  if (!reached) {
    plan.message = "no path: the goal cannot be reached from the start";
    return plan;
  }
  for (std::int64_t at = goal_offset; at != kNoParent; at = parent[at]) {
    plan.cells.push_back(HexLattice::FromIndex(rect.IndexAt(at)));
  }
  std::reverse(plan.cells.begin(), plan.cells.end());
  plan.waypoints.push_back(start);
  for (std::size_t i = 1; i + 1 < plan.cells.size(); ++i) {
    plan.waypoints.push_back(lattice.CentreOf(plan.cells[i]));
  }
  plan.waypoints.push_back(goal_cell == lattice.CellOf(goal) ? goal : lattice.CentreOf(goal_cell));
  plan.cell_path_length = PathLength(plan.waypoints);
  if (options.smooth) plan.waypoints = PullTaut(map, cells, plan, options);
  plan.length = PathLength(plan.waypoints);
  plan.found = true;
  return plan;
}

}  // namespace hex_slam
