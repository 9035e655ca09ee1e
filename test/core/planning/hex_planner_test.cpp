#include "hex_slam/planning/hex_planner.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/ray_traversal.h"

namespace hex_slam {
namespace {

constexpr double kSpacing = 0.05;
constexpr float kFree = -2.0f;
constexpr float kWall = 5.0f;
const OccupancyModel kModel = OccupancyModel::FromFactors(0.4, 0.9, 50.0);

GridMap<HexLattice> EmptyMap(double width, double height) {
  return GridMap<HexLattice>(HexLattice(kSpacing), kModel, GridGrowthPolicy(),
                             Eigen::AlignedBox2d(Eigen::Vector2d(0.0, 0.0),
                                                 Eigen::Vector2d(width, height)));
}

double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::max(0.0, std::min(1.0, (p - a).dot(ab) / ab.squaredNorm()));
  return (a + t * ab - p).norm();
}

struct Segment {
  Eigen::Vector2d a, b;
};

// Two 2 m × 2 m rooms side by side, the wall between them at x = 2 with a door of `door` m at
// y in [0.9, 0.9 + door] (no door when 0). Everything inside is known free.
GridMap<HexLattice> TwoRooms(double door) {
  GridMap<HexLattice> map = EmptyMap(4.2, 2.2);
  std::vector<Segment> walls = {{{0.05, 0.05}, {4.05, 0.05}}, {{0.05, 2.05}, {4.05, 2.05}},
                                {{0.05, 0.05}, {0.05, 2.05}}, {{4.05, 0.05}, {4.05, 2.05}},
                                {{2.0, 0.05}, {2.0, 0.9}}};
  walls.push_back(door > 0.0 ? Segment{{2.0, 0.9 + door}, {2.0, 2.05}}
                             : Segment{{2.0, 0.9}, {2.0, 2.05}});
  std::vector<float> log_odds(map.rect().size(), 0.0f);
  for (std::size_t i = 0; i < log_odds.size(); ++i) {
    const Eigen::Vector2d c = map.lattice().CentreOf(map.rect().IndexAt(i));
    const bool inside = c.x() > 0.0 && c.x() < 4.1 && c.y() > 0.0 && c.y() < 2.1;
    if (!inside) continue;
    log_odds[i] = kFree;
    for (const Segment& w : walls) {
      if (SegmentDistance(c, w.a, w.b) < 0.6 * kSpacing) log_odds[i] = kWall;
    }
  }
  map.Assign(map.rect(), log_odds);
  return map;
}

bool AreNeighbours(const HexCell& x, const HexCell& y) { return HexDistance(x, y) == 1; }

// Breadth-first search over the cells the planner may enter: the fewest steps, or -1.
int BreadthFirstSteps(const GridMap<HexLattice>& map, const PlannerCells& cells,
                      const HexCell& start, const HexCell& goal, bool allow_unknown) {
  const GridRect& rect = map.rect();
  std::vector<int> steps(rect.size(), -1);
  std::deque<HexCell> queue = {start};
  steps[rect.Offset(HexLattice::ToIndex(start))] = 0;
  while (!queue.empty()) {
    const HexCell c = queue.front();
    queue.pop_front();
    const int here = steps[rect.Offset(HexLattice::ToIndex(c))];
    if (c == goal) return here;
    for (int k = 0; k < 6; ++k) {
      const HexCell n{c.a + kHexNeighbourDa[k], c.b + kHexNeighbourDb[k]};
      const GridIndex index = HexLattice::ToIndex(n);
      if (!rect.Contains(index)) continue;
      if (!MayStep(cells, rect.Offset(HexLattice::ToIndex(c)), rect.Offset(index), allow_unknown)) {
        continue;
      }
      int& s = steps[rect.Offset(index)];
      if (s >= 0) continue;
      s = here + 1;
      queue.push_back(n);
    }
  }
  return -1;
}

// What ClassifyCells promises, cell by cell, from every pair of cells.
void CheckClassification(const GridMap<HexLattice>& map, const HexPlannerOptions& options) {
  const PlannerCells cells = ClassifyCells(map.log_odds_grid(), options);
  const GridRect& rect = map.rect();
  const HexLattice& lattice = map.lattice();
  auto occupied = [&](std::size_t i) {
    return map.ProbabilityAt(map.rect().IndexAt(i)) >= options.occupied_probability;
  };
  auto unknown = [&](std::size_t i) { return !occupied(i) && map.log_odds_grid().data()[i] == 0.0f; };
  auto unknown_edge = [&](std::size_t i) {
    if (!unknown(i)) return false;
    const HexCell c = HexLattice::FromIndex(rect.IndexAt(i));
    for (std::size_t j = 0; j < rect.size(); ++j) {
      if (!unknown(j) && HexDistance(c, HexLattice::FromIndex(rect.IndexAt(j))) == 1) return true;
    }
    return false;
  };
  const bool clear_of_unknown = options.keep_clear_of_unknown && !options.allow_unknown;
  for (std::size_t i = 0; i < rect.size(); ++i) {
    Traversability expected = Traversability::kFree;
    float clearance = std::numeric_limits<float>::infinity();
    if (occupied(i)) {
      expected = Traversability::kOccupied;
    } else if (unknown(i) && !options.allow_unknown) {
      expected = Traversability::kUnknown;
    } else {
      const Eigen::Vector2d c = lattice.CentreOf(rect.IndexAt(i));
      for (std::size_t j = 0; j < rect.size(); ++j) {
        if (!occupied(j) && !(clear_of_unknown && unknown_edge(j))) continue;
        const float d = static_cast<float>((lattice.CentreOf(rect.IndexAt(j)) - c).norm());
        if (d <= options.robot_radius) clearance = std::min(clearance, d);
      }
      if (std::isfinite(clearance)) {
        expected = Traversability::kInflated;
      } else if (unknown(i)) {
        expected = Traversability::kUnknown;
      }
    }
    ASSERT_EQ(static_cast<int>(cells.kind[i]), static_cast<int>(expected)) << "cell " << i;
    if (expected == Traversability::kInflated) {
      ASSERT_NEAR(cells.clearance[i], clearance, 1e-6) << "cell " << i;
    }
  }
}

TEST(HexPlannerTest, ClassificationMatchesBruteForce) {
  GridMap<HexLattice> map = EmptyMap(1.0, 0.8);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> log_odds(map.rect().size());
  for (float& v : log_odds) {
    const float r = u(rng);
    v = r < 0.05f ? kWall : r < 0.12f ? 0.0f : r < 0.17f ? 0.3f : kFree;  // 0.3: 0.57, not a wall
  }
  map.Assign(map.rect(), log_odds);
  HexPlannerOptions options;
  options.robot_radius = 0.12;
  CheckClassification(map, options);
  options.keep_clear_of_unknown = false;
  CheckClassification(map, options);
  options.allow_unknown = true;
  CheckClassification(map, options);
}

TEST(HexPlannerTest, PathsAreShortestAgainstBreadthFirstSearch) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int found = 0, unreachable = 0;
  for (int trial = 0; trial < 60; ++trial) {
    GridMap<HexLattice> map = EmptyMap(1.5, 1.0);
    std::vector<float> log_odds(map.rect().size());
    const float walls = 0.1f + 0.1f * (trial % 4);  // up to 40 %: some goals cut off
    for (float& v : log_odds) v = u(rng) < walls ? kWall : u(rng) < 0.1f ? 0.0f : kFree;
    map.Assign(map.rect(), log_odds);
    HexPlannerOptions options;
    options.robot_radius = trial % 3 == 0 ? 0.0 : 0.04;
    options.allow_unknown = trial % 2 == 0;
    const Eigen::Vector2d start(0.1 + 1.3 * u(rng), 0.1 + 0.8 * u(rng));
    const Eigen::Vector2d goal(0.1 + 1.3 * u(rng), 0.1 + 0.8 * u(rng));
    const HexPlan plan = PlanHexPath(map.log_odds_grid(), start, goal, options);
    const PlannerCells cells = ClassifyCells(map.log_odds_grid(), options);
    const HexCell s = map.lattice().CellOf(start), g = map.lattice().CellOf(goal);
    const Traversability at_start = cells.kind[map.rect().Offset(HexLattice::ToIndex(s))];
    const Traversability at_goal = cells.kind[map.rect().Offset(HexLattice::ToIndex(g))];
    const bool goal_ok = at_goal == Traversability::kFree ||
                         (options.allow_unknown && at_goal == Traversability::kUnknown);
    if (at_start == Traversability::kOccupied || !goal_ok) {
      EXPECT_FALSE(plan.found);
      continue;
    }
    const int steps = BreadthFirstSteps(map, cells, s, g, options.allow_unknown);
    ASSERT_EQ(plan.found, steps >= 0) << "trial " << trial << ": " << plan.message;
    if (!plan.found) {
      ++unreachable;
      continue;
    }
    ++found;
    ASSERT_EQ(static_cast<int>(plan.cells.size()) - 1, steps) << "trial " << trial;
    EXPECT_EQ(plan.cells.front(), s);
    EXPECT_EQ(plan.cells.back(), g);
    for (std::size_t i = 1; i < plan.cells.size(); ++i) {
      ASSERT_TRUE(AreNeighbours(plan.cells[i - 1], plan.cells[i]));
      EXPECT_TRUE(MayStep(cells, map.rect().Offset(HexLattice::ToIndex(plan.cells[i - 1])),
                          map.rect().Offset(HexLattice::ToIndex(plan.cells[i])),
                          options.allow_unknown));
    }
  }
  EXPECT_GT(found, 20);  // both outcomes are exercised
  EXPECT_GT(unreachable, 0);
}

TEST(HexPlannerTest, ThroughTheDoorKeepingClearOfTheWalls) {
  const GridMap<HexLattice> map = TwoRooms(0.5);
  HexPlannerOptions options;
  options.robot_radius = 0.15;
  const Eigen::Vector2d start(0.5, 0.5), goal(3.5, 1.6);
  const HexPlan plan = PlanHexPath(map.log_odds_grid(), start, goal, options);
  ASSERT_TRUE(plan.found) << plan.message;
  EXPECT_EQ(plan.waypoints.front(), start);
  EXPECT_EQ(plan.waypoints.back(), goal);
  // Across the wall only through the door, and never within the radius of a wall cell.
  const GridRect& rect = map.rect();
  for (std::size_t i = 1; i < plan.waypoints.size(); ++i) {
    const Eigen::Vector2d& p = plan.waypoints[i - 1];
    const Eigen::Vector2d& q = plan.waypoints[i];
    if ((p.x() - 2.0) * (q.x() - 2.0) <= 0.0 && p.x() != q.x()) {
      const double y = p.y() + (2.0 - p.x()) / (q.x() - p.x()) * (q.y() - p.y());
      EXPECT_GT(y, 0.9 + options.robot_radius - kSpacing);
      EXPECT_LT(y, 1.4 - options.robot_radius + kSpacing);
    }
  }
  for (std::size_t k = 1; k < plan.cells.size(); ++k) {
    const Eigen::Vector2d c = map.lattice().CentreOf(plan.cells[k]);
    for (std::size_t j = 0; j < rect.size(); ++j) {
      if (map.ProbabilityAt(rect.IndexAt(j)) < options.occupied_probability) continue;
      ASSERT_GT((map.lattice().CentreOf(rect.IndexAt(j)) - c).norm(), options.robot_radius);
    }
  }
  // A detour through the door: longer than the straight line, not by much.
  const double straight = (goal - start).norm();
  EXPECT_GT(plan.length, straight);
  EXPECT_LT(plan.length, 1.4 * straight);
}

TEST(HexPlannerTest, OpenSpacePathsStayWithinTheHexDetourOfAStraightLine) {
  const GridMap<HexLattice> map = TwoRooms(0.5);
  HexPlannerOptions options;
  options.robot_radius = 0.1;
  options.smooth = false;  // the cell path itself
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(0.3, 1.7), y(0.3, 1.7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector2d start(x(rng), y(rng)), goal(x(rng), y(rng));
    const HexPlan plan = PlanHexPath(map.log_odds_grid(), start, goal, options);
    ASSERT_TRUE(plan.found) << plan.message;
    // Six directions 60° apart: the shortest lattice path is at most 2/sqrt(3) of the line, plus
    // a cell at each end.
    EXPECT_LE(plan.length, 2.0 / std::sqrt(3.0) * (goal - start).norm() + 2.0 * kSpacing);
  }
}

// Pulled taut: every segment crosses (exact traversal) only cells the planner may use, the path
// is no longer than the cell path, and in open space it is the straight line.
TEST(HexPlannerTest, SmoothedPathsAreTautAndStayOnUsableCells) {
  const GridMap<HexLattice> map = TwoRooms(0.5);
  HexPlannerOptions options;
  options.robot_radius = 0.15;
  const PlannerCells cells = ClassifyCells(map.log_odds_grid(), options);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> x(0.3, 3.7), y(0.3, 1.7);
  std::vector<HexCell> crossed;
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::Vector2d start(x(rng), y(rng)), goal(x(rng), y(rng));
    const HexPlan plan = PlanHexPath(map.log_odds_grid(), start, goal, options);
    if (!plan.found) continue;
    EXPECT_LE(plan.length, plan.cell_path_length + 1e-9);
    EXPECT_EQ(plan.waypoints.front(), start);
    EXPECT_EQ(plan.waypoints.back(), goal);
    std::vector<bool> on_path(map.rect().size(), false);
    for (const HexCell& c : plan.cells) on_path[map.rect().Offset(HexLattice::ToIndex(c))] = true;
    for (std::size_t i = 1; i < plan.waypoints.size(); ++i) {
      TraceRay(map.lattice(), plan.waypoints[i - 1], plan.waypoints[i], &crossed);
      crossed.push_back(map.lattice().CellOf(plan.waypoints[i]));
      for (const HexCell& c : crossed) {
        const std::size_t o = map.rect().Offset(HexLattice::ToIndex(c));
        ASSERT_TRUE(on_path[o] || cells.kind[o] == Traversability::kFree) << "trial " << trial;
      }
    }
    const bool same_room = (start.x() - 2.0) * (goal.x() - 2.0) > 0.0;
    if (same_room) {
      // Nothing in the way inside a room: the line itself, give or take the end cells.
      EXPECT_LT(plan.length, (goal - start).norm() + 2.0 * kSpacing) << "trial " << trial;
    }
  }
  options.smooth = false;
  const HexPlan raw = PlanHexPath(map.log_odds_grid(), {0.5, 0.5}, {1.5, 1.4}, options);
  ASSERT_TRUE(raw.found);
  EXPECT_EQ(raw.waypoints.size(), raw.cells.size());
  EXPECT_DOUBLE_EQ(raw.length, raw.cell_path_length);
}

TEST(HexPlannerTest, ResampledPathsKeepTheCornersAndTheLength) {
  const std::vector<Eigen::Vector2d> corners = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.25}};
  const std::vector<Eigen::Vector2d> dense = ResamplePath(corners, 0.1);
  ASSERT_EQ(dense.size(), 1u + 10u + 3u);
  EXPECT_EQ(dense.front(), corners.front());
  EXPECT_TRUE(dense[10].isApprox(corners[1]));
  EXPECT_EQ(dense.back(), corners.back());
  double length = 0.0;
  for (std::size_t i = 1; i < dense.size(); ++i) {
    const double step = (dense[i] - dense[i - 1]).norm();
    EXPECT_LE(step, 0.1 + 1e-12);
    length += step;
  }
  EXPECT_NEAR(length, 1.25, 1e-12);
  EXPECT_TRUE(ResamplePath({}, 0.1).empty());
}

TEST(HexPlannerTest, AClosedDoorHasNoPath) {
  const HexPlan plan = PlanHexPath(TwoRooms(0.0).log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, HexPlannerOptions());
  EXPECT_FALSE(plan.found);
  EXPECT_NE(plan.message.find("no path"), std::string::npos) << plan.message;
}

TEST(HexPlannerTest, ADoorNarrowerThanTheRobotHasNoPath) {
  HexPlannerOptions options;
  options.robot_radius = 0.3;  // a 0.6 m robot and a 0.5 m door
  EXPECT_FALSE(PlanHexPath(TwoRooms(0.5).log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, options).found);
  options.robot_radius = 0.15;
  EXPECT_TRUE(PlanHexPath(TwoRooms(0.5).log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, options).found);
}

TEST(HexPlannerTest, AGoalInAWallMovesOnlyWithinTheTolerance) {
  const GridMap<HexLattice> map = TwoRooms(0.5);
  const Eigen::Vector2d goal(2.0, 0.4);  // on the wall between the rooms
  HexPlannerOptions options;
  options.robot_radius = 0.1;
  const HexPlan refused = PlanHexPath(map.log_odds_grid(), {0.5, 0.5}, goal, options);
  EXPECT_FALSE(refused.found);
  EXPECT_NE(refused.message.find("goal"), std::string::npos) << refused.message;
  options.goal_tolerance = 0.3;
  const HexPlan moved = PlanHexPath(map.log_odds_grid(), {0.5, 0.5}, goal, options);
  ASSERT_TRUE(moved.found) << moved.message;
  EXPECT_LE((moved.waypoints.back() - goal).norm(), options.goal_tolerance);
  EXPECT_GT((moved.waypoints.back() - goal).norm(), options.robot_radius);  // clear of the wall
}

TEST(HexPlannerTest, UnknownSpaceIsEnteredOnlyWhenAllowed) {
  GridMap<HexLattice> map = TwoRooms(0.5);
  // Forget the right room.
  std::vector<float> log_odds = map.log_odds_grid().values();
  for (std::size_t i = 0; i < log_odds.size(); ++i) {
    if (map.lattice().CentreOf(map.rect().IndexAt(i)).x() > 2.1) log_odds[i] = 0.0f;
  }
  map.Assign(map.rect(), log_odds);
  HexPlannerOptions options;
  options.robot_radius = 0.1;
  EXPECT_FALSE(PlanHexPath(map.log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, options).found);
  options.allow_unknown = true;
  EXPECT_TRUE(PlanHexPath(map.log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, options).found);
}

TEST(HexPlannerTest, AStartNearAWallLeadsOutAStartInOneIsRefused) {
  const GridMap<HexLattice> map = TwoRooms(0.5);
  HexPlannerOptions options;
  options.robot_radius = 0.2;
  const HexPlan out = PlanHexPath(map.log_odds_grid(), {0.15, 1.0}, {1.0, 1.0}, options);  // 0.1 m off the wall
  ASSERT_TRUE(out.found) << out.message;
  // Out of the band and never back into it: each cell near the wall farther than the last.
  const PlannerCells cells = ClassifyCells(map.log_odds_grid(), options);
  float last = 0.0f;
  bool left = false;
  for (const HexCell& c : out.cells) {
    const std::size_t o = map.rect().Offset(HexLattice::ToIndex(c));
    if (cells.kind[o] == Traversability::kInflated) {
      EXPECT_FALSE(left) << "the path came back into the band";
      EXPECT_GT(cells.clearance[o], last);
      last = cells.clearance[o];
    } else {
      left = true;
    }
  }
  EXPECT_TRUE(left);
  const HexPlan inside = PlanHexPath(map.log_odds_grid(), {0.05, 1.0}, {1.0, 1.0}, options);
  EXPECT_FALSE(inside.found);
  EXPECT_NE(inside.message.find("start"), std::string::npos) << inside.message;
}

TEST(HexPlannerTest, NonFiniteEndsAreRefused) {
  const GridMap<HexLattice> map = TwoRooms(0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& bad : {Eigen::Vector2d(nan, 1.0), Eigen::Vector2d(1.0, inf)}) {
    const HexPlan a = PlanHexPath(map.log_odds_grid(), bad, {1.0, 1.0}, HexPlannerOptions());
    const HexPlan b = PlanHexPath(map.log_odds_grid(), {1.0, 1.0}, bad, HexPlannerOptions());
    EXPECT_FALSE(a.found);
    EXPECT_FALSE(b.found);
    EXPECT_NE(a.message.find("finite"), std::string::npos);
  }
  // Far outside the map (where cell indices would overflow int): refused, not undefined.
  const HexPlan far = PlanHexPath(map.log_odds_grid(), {1.0, 1.0}, {1e12, -1e12}, HexPlannerOptions());
  EXPECT_FALSE(far.found);
  EXPECT_NE(far.message.find("outside the map"), std::string::npos) << far.message;
  EXPECT_FALSE(PlanHexPath(map.log_odds_grid(), {-1e15, 0.0}, {1.0, 1.0}, HexPlannerOptions()).found);
}

TEST(HexPlannerTest, InflationOverItsBudgetIsRefusedBeforeItRuns) {
  // Issue 12: hex_slam_plan on a map of 0.1 mm cells took 26 s (here: a 5 cm x 5 cm box, whose
  // 0.2 m robot disc alone holds 14.5 million cells). Refused, and said why.
  GridMap<HexLattice> fine(HexLattice(1e-4), kModel, GridGrowthPolicy(),
                           Eigen::AlignedBox2d(Eigen::Vector2d(0.0, 0.0),
                                               Eigen::Vector2d(0.05, 0.05)));
  std::vector<float> log_odds(fine.rect().size(), kFree);
  for (std::size_t i = 0; i < log_odds.size(); ++i) {
    if (std::abs(fine.lattice().CentreOf(fine.rect().IndexAt(i)).x() - 0.04) < 1e-4) {
      log_odds[i] = kWall;
    }
  }
  fine.Assign(fine.rect(), log_odds);
  const HexPlan refused = PlanHexPath(fine.log_odds_grid(), {0.01, 0.01}, {0.02, 0.03}, HexPlannerOptions());
  EXPECT_FALSE(refused.found);
  EXPECT_NE(refused.message.find("max_inflation_steps"), std::string::npos) << refused.message;
  EXPECT_EQ(refused.expansions, 0);
  HexPlannerOptions small;
  small.robot_radius = 0.002;  // 20 cells: fine
  EXPECT_TRUE(PlanHexPath(fine.log_odds_grid(), {0.01, 0.01}, {0.02, 0.03}, small).found);
  small.goal_tolerance = 10.0;  // a disc of 10^10 cells to search for a free goal cell
  const HexPlan wide = PlanHexPath(fine.log_odds_grid(), {0.01, 0.01}, {0.02, 0.03}, small);
  EXPECT_NE(wide.message.find("goal_tolerance"), std::string::npos) << wide.message;

  // The budget is the product of the cells to keep clear of and the disc's: on the two rooms
  // (measured from ClassifyCells below), a budget between 0.2 m's and 0.5 m's products admits
  // the first radius and refuses the second.
  const GridMap<HexLattice> rooms = TwoRooms(0.5);
  HexPlannerOptions options;
  const PlannerCells cells = ClassifyCells(rooms.log_odds_grid(), options);
  ASSERT_TRUE(cells.refused.empty());
  std::size_t walls = 0;
  for (const Traversability t : cells.kind) walls += t == Traversability::kOccupied;
  // The planner's estimate of a 0.5 m disc's cells; the 0.2 m one holds 0.16 of them, and the
  // cells to keep clear of (walls and the unknown's edge) are fewer than 5 per wall cell here.
  const double disc = M_PI * 0.5 * 0.5 / HexLattice(kSpacing).cell_area() + 1.0;
  options.max_inflation_steps = static_cast<std::int64_t>(0.9 * walls * disc);
  EXPECT_TRUE(PlanHexPath(rooms.log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, options).found);  // 0.2 m
  options.robot_radius = 0.5;
  const HexPlan over = PlanHexPath(rooms.log_odds_grid(), {0.5, 0.5}, {3.5, 1.6}, options);
  EXPECT_FALSE(over.found);
  EXPECT_NE(over.message.find("inflating"), std::string::npos) << over.message;
  HexPlannerOptions zero;
  zero.max_inflation_steps = 0;
  EXPECT_EQ(zero.Validate().size(), 1u);
}

TEST(HexPlannerTest, ATenMetreRobotOnABigMapIsRefusedWithTheDefaultBudget) {
  // Issue 12: --robot-radius 10 on the Intel map took 18-21 s. Here a 40 m square hall at 5 cm:
  // ~3,700 wall cells times a 145,000-cell disc is 5e8 steps, over the default 1.3e8.
  GridMap<HexLattice> hall = EmptyMap(40.0, 40.0);
  std::vector<float> log_odds(hall.rect().size(), 0.0f);
  for (std::size_t i = 0; i < log_odds.size(); ++i) {
    const Eigen::Vector2d c = hall.lattice().CentreOf(hall.rect().IndexAt(i));
    const double edge = std::min({c.x(), c.y(), 40.0 - c.x(), 40.0 - c.y()});
    log_odds[i] = edge < 0.5 ? 0.0f : edge < 0.55 ? kWall : kFree;
  }
  hall.Assign(hall.rect(), log_odds);
  HexPlannerOptions options;
  options.robot_radius = 10.0;
  const HexPlan refused = PlanHexPath(hall.log_odds_grid(), {15.0, 15.0}, {25.0, 25.0}, options);
  EXPECT_FALSE(refused.found);
  EXPECT_NE(refused.message.find("max_inflation_steps"), std::string::npos) << refused.message;
  options.robot_radius = 1.0;  // 3,700 x 1,450: planned
  EXPECT_TRUE(PlanHexPath(hall.log_odds_grid(), {15.0, 15.0}, {25.0, 25.0}, options).found);
}

TEST(HexPlannerTest, BadOptionsAreNamed) {
  HexPlannerOptions options;
  options.robot_radius = -1.0;
  options.occupied_probability = 0.3;
  EXPECT_EQ(options.Validate().size(), 2u);
  HexPlannerOptions huge;
  huge.goal_tolerance = 1e12;
  EXPECT_EQ(huge.Validate().size(), 1u);
  const HexPlan plan = PlanHexPath(TwoRooms(0.5).log_odds_grid(), {0.5, 0.5}, {1.0, 1.0}, options);
  EXPECT_FALSE(plan.found);
  EXPECT_NE(plan.message.find("robot_radius"), std::string::npos);
}

}  // namespace
}  // namespace hex_slam
