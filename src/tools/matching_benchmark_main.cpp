// hex_slam_matching_bench (Google Benchmark): the branch-and-bound correlative matcher on both
// lattices, on a map of the 10 m × 8 m test room at 5 cm cells from five noise-free scans.
// Times the precomputation of a map's grids, the local search (±window m, ±30°, the robot's true
// pose up to a metre and 15° from the guess) and the full-map search; the counters give the
// candidates scored per search and, for comparison, the size of the exhaustive window. Then the
// front end's recovery search (SearchCorrelative on the pyramid's 0.2 m level) over its first
// window (±0.4 m, ±0.6 rad), its wide one (±0.8 m, every heading) and the search while lost
// (±1 m, every heading), by branch and bound (bounded:1) and pose by pose (bounded:0):
// the same poses, so their times compare directly.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/matching/correlative_search.h"
#include "hex_slam/matching/fast_correlative_scan_matcher.h"
#include "hex_slam/sensor/scan_sanitizer.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/sim/segment_world.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace {

constexpr double kSpacing = 0.05;  // m

sim::SegmentWorld Room() {
  return sim::SegmentWorld::TestRoom().Transformed(sim::GenericRoomPlacement());
}

std::vector<Eigen::Vector2d> Scan(const sim::World& world, const Pose2& pose, int beams,
                                  std::mt19937_64* rng) {
  sim::LidarModel lidar;
  lidar.beams = beams;
  lidar.range_noise_stddev = 0.01;
  std::vector<Eigen::Vector2d> points;
  BeamCounts counts;
  std::string message;
  SanitizeScan(sim::SimulateScan(world, pose, lidar, 0.0, rng), RangeFilter{}, &points, &counts,
               &message);
  return points;
}

template <class Lattice>
MapPyramid<Lattice> RoomMaps(int levels) {
  MapPyramid<Lattice> m(kSpacing, levels, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                        GridGrowthPolicy(),
                        Eigen::AlignedBox2d(Eigen::Vector2d(-7, -6), Eigen::Vector2d(7, 6)));
  const sim::SegmentWorld world = Room();
  std::mt19937_64 rng(0);
  for (const Pose2& p : {Pose2(0, 0, 0), Pose2(-2.5, 1.0, 0.3), Pose2(3.2, -0.5, -1.0),
                         Pose2(-3.5, -2.0, 2.0), Pose2(2.5, 3.0, 0.7)}) {
    const Pose2 pose = sim::GenericRoomPlacement() * p;
    std::vector<Eigen::Vector2d> world_points;
    for (const auto& q : Scan(world, pose, 720, &rng)) world_points.push_back(pose * q);
    m.InsertScan(pose.translation(), world_points);
  }
  return m;
}

template <class Lattice>
const GridMap<Lattice>& RoomMap() {
  static const MapPyramid<Lattice> maps = RoomMaps<Lattice>(1);
  return maps.level(0);
}

// 16 scans from random poses in the room, each with a guess off the truth by up to `linear` (m,
// along each axis) and `angular` (rad).
struct Trial {
  Pose2 guess;
  std::vector<Eigen::Vector2d> points;
};
std::vector<Trial> Trials(std::uint64_t seed, double linear, double angular) {
  const sim::SegmentWorld world = Room();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Trial> trials;
  for (int i = 0; i < 16; ++i) {
    const Pose2 truth = sim::GenericRoomPlacement() * Pose2(u(rng), u(rng), M_PI * u(rng));
    trials.push_back({Pose2(truth.x + linear * u(rng), truth.y + linear * u(rng),
                            truth.theta + angular * u(rng)),
                      Scan(world, truth, 360, &rng)});
  }
  return trials;
}

template <class Lattice>
void BM_Precompute(benchmark::State& state) {
  matching::FastCorrelativeScanMatcherOptions options;
  options.branch_and_bound_depth = static_cast<int>(state.range(0));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const matching::FastCorrelativeScanMatcher<Lattice> matcher(RoomMap<Lattice>(), options);
    bytes = matcher.MemoryBytes();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["MB"] = bytes / 1e6;
}

template <class Lattice>
void BM_LocalSearch(benchmark::State& state) {
  matching::FastCorrelativeScanMatcherOptions options;
  options.linear_search_window = static_cast<double>(state.range(0));
  const matching::FastCorrelativeScanMatcher<Lattice> matcher(RoomMap<Lattice>(), options);
  const std::vector<Trial> trials = Trials(1, 1.0, 0.25);
  long candidates = 0, searches = 0, window = 0;
  for (const Trial& t : trials) {
    for (const matching::DiscreteScan& s : matcher.Window(t.guess, t.points, options.linear_search_window, options.angular_search_window)) {
      window += static_cast<long>(s.max_offset.x() - s.min_offset.x() + 1) *
                (s.max_offset.y() - s.min_offset.y() + 1);
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const Trial& t = trials[i++ % trials.size()];
    const auto match = matcher.Match(t.guess, t.points, 0.5);
    candidates += match ? match->candidates : 0;
    ++searches;
  }
  state.counters["scored"] = static_cast<double>(candidates) / searches;
  state.counters["window"] = static_cast<double>(window) / trials.size();
}

template <class Lattice>
void BM_FullSubmapSearch(benchmark::State& state) {
  const matching::FastCorrelativeScanMatcher<Lattice> matcher(
      RoomMap<Lattice>(), matching::FastCorrelativeScanMatcherOptions());
  std::mt19937_64 rng(2);
  const auto points = Scan(Room(), sim::GenericRoomPlacement() * Pose2(0.7, -0.4, 2.0), 360, &rng);
  long candidates = 0, searches = 0;
  for (auto _ : state) {
    const auto match = matcher.MatchFullSubmap(points, 0.5);
    candidates += match ? match->candidates : 0;
    ++searches;
  }
  state.counters["scored"] = static_cast<double>(candidates) / searches;
}

// range(0): 0 the first recovery window, 1 the wide one, 2 the search while lost (±1 m, every
// heading); range(1): 1 branch and bound, 0 every pose scored. The guesses are up to 0.3 m and
// 0.4 rad off the truth.
template <class Lattice>
void BM_RecoverySearch(benchmark::State& state) {
  static const MapPyramid<Lattice> maps = RoomMaps<Lattice>(3);
  const GridMap<Lattice>& coarse = maps.level(2);
  CorrelativeSearchOptions options;
  if (state.range(0) == 1) {
    options.linear_window = 0.8;
    options.angular_window = M_PI;
    options.max_step_coarsening = 2.0;  // as Slam's wide recovery allows
  } else if (state.range(0) == 2) {  // the search while lost, every heading at once
    options.linear_window = 1.0;
    options.angular_window = M_PI;
  }
  options.branch_and_bound = state.range(1) == 1;
  const std::vector<Trial> trials = Trials(3, 0.3, 0.4);
  long poses = 0, bounded = 0, searches = 0;
  for (auto _ : state) {
    const Trial& t = trials[searches++ % trials.size()];
    const CorrelativeResult r = SearchCorrelative(coarse, t.points, t.guess, options);
    poses += r.candidates;
    bounded += r.branch_and_bound ? 1 : 0;
    benchmark::DoNotOptimize(r.score);
  }
  state.counters["poses"] = static_cast<double>(poses) / searches;
  state.counters["bounded"] = static_cast<double>(bounded) / searches;
}

BENCHMARK_TEMPLATE(BM_Precompute, HexLattice)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Precompute, SquareLattice)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_LocalSearch, HexLattice)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_LocalSearch, SquareLattice)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_FullSubmapSearch, HexLattice)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_FullSubmapSearch, SquareLattice)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_RecoverySearch, HexLattice)
    ->ArgsProduct({{0, 1, 2}, {1, 0}})
    ->ArgNames({"window", "bounded"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_RecoverySearch, SquareLattice)
    ->ArgsProduct({{0, 1, 2}, {1, 0}})
    ->ArgNames({"window", "bounded"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hex_slam

BENCHMARK_MAIN();
