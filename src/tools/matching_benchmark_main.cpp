// hex_slam_matching_bench (Google Benchmark): the branch-and-bound correlative matcher on both
// lattices, on a map of the 10 m × 8 m test room at 5 cm cells from five noise-free scans.
// Times the precomputation of a map's grids, the local search (±window m, ±30°, the robot's true
// pose up to a metre and 15° from the guess) and the full-map search; the counters give the
// candidates scored per search and, for comparison, the size of the exhaustive window.
#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/map/map_pyramid.h"
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
const GridMap<Lattice>& RoomMap() {
  static const MapPyramid<Lattice> maps = [] {
    MapPyramid<Lattice> m(kSpacing, 1, OccupancyModel::FromFactors(0.4, 0.9, 50.0),
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
  }();
  return maps.level(0);
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
  const sim::SegmentWorld world = Room();
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  struct Trial {
    Pose2 guess;
    std::vector<Eigen::Vector2d> points;
  };
  std::vector<Trial> trials;
  for (int i = 0; i < 16; ++i) {
    const Pose2 truth = sim::GenericRoomPlacement() * Pose2(u(rng), u(rng), M_PI * u(rng));
    trials.push_back({Pose2(truth.x + u(rng), truth.y + u(rng), truth.theta + 0.25 * u(rng)),
                      Scan(world, truth, 360, &rng)});
  }
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

BENCHMARK_TEMPLATE(BM_Precompute, HexLattice)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Precompute, SquareLattice)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_LocalSearch, HexLattice)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_LocalSearch, SquareLattice)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_FullSubmapSearch, HexLattice)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_FullSubmapSearch, SquareLattice)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hex_slam

BENCHMARK_MAIN();
