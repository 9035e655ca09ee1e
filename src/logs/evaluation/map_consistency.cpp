#include "hex_slam/logs/evaluation/map_consistency.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/sensor/scan_sanitizer.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace logs {
namespace {

constexpr double kLowQuantile = 0.05;
constexpr double kInitialHalfSide = 5.0;  // m

template <class Lattice>
std::vector<double> ScoreScans(const std::vector<LogScan>& scans, const std::vector<Pose2>& poses,
                               const SlamOptions& options) {
  const std::size_t n = std::min(scans.size(), poses.size());
  const RangeFilter filter{options.laser_min_dist, options.laser_max_dist,
                           options.laser_range_max_is_no_return, options.laser_range_max_margin};
  ScanSanitizer sanitizer;
  std::vector<std::vector<Eigen::Vector2d>> endpoints(n);
  std::vector<Eigen::Vector2d> origins(n);
  std::vector<Eigen::Vector2d> sensor_points;
  std::optional<Eigen::Vector2d> first_origin;
  for (std::size_t i = 0; i < n; ++i) {
    BeamCounts counts;
    std::string message;
    if (sanitizer.Sanitize(scans[i].scan, filter, &sensor_points, &counts, &message) !=
        ScanError::kNone) {
      continue;
    }
    const Pose2 sensor = poses[i] * scans[i].sensor_pose;
    origins[i] = sensor.translation();
    if (!first_origin) first_origin = origins[i];
    const PointTransform to_map(sensor);
    for (const Eigen::Vector2d& p : sensor_points) endpoints[i].push_back(to_map(p));
  }
  GridGrowthPolicy growth;
  growth.max_cells = options.map_max_cells;
  const OccupancyModel model = OccupancyModel::FromFactors(
      options.update_factor_free, options.update_factor_occupied, options.log_odds_limit);
  // Storage starts small and grows with the scans up to map_max_cells (the cells' values do not
  // depend on it): a trajectory that ran off — hundreds of metres — is scored, not refused.
  // On fine cells 10 m may already exceed map_max_cells: then a quarter of the cap's side.
  const Eigen::Vector2d centre = first_origin.value_or(Eigen::Vector2d::Zero());
  const double fitting = 0.25 * std::sqrt(static_cast<double>(options.map_max_cells)) *
                         options.map_resolution;
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(std::min(kInitialHalfSide, fitting));
  GridMap<Lattice> grid(Lattice(options.map_resolution), model, growth,
                        Eigen::AlignedBox2d(centre - half, centre + half));
  // All the storage at once where the cap allows: grown scan by scan, a long-range log's grid is
  // copied into larger storage many times.
  Eigen::AlignedBox2d all;
  for (std::size_t i = 0; i < n; ++i) {
    if (endpoints[i].empty()) continue;
    all.extend(origins[i]);
    for (const Eigen::Vector2d& p : endpoints[i]) all.extend(p);
  }
  if (!all.isEmpty()) grid.EnsureCovers(all);
  for (std::size_t i = 0; i < n; ++i) {
    if (!endpoints[i].empty()) grid.InsertScan(origins[i], endpoints[i]);
  }
  std::vector<double> scores;
  for (std::size_t i = 0; i < n; ++i) {
    if (endpoints[i].empty()) continue;
    double sum = 0.0;
    for (const Eigen::Vector2d& p : endpoints[i]) sum += grid.Probability(grid.lattice().CellOf(p));
    scores.push_back(sum / endpoints[i].size());
  }
  return scores;
}

}  // namespace

MapConsistencyReport EvaluateMapConsistency(const std::vector<LogScan>& scans,
                                            const std::vector<Pose2>& poses,
                                            const SlamOptions& options) {
  std::vector<double> scores = options.lattice == "square"
                                   ? ScoreScans<SquareLattice>(scans, poses, options)
                                   : ScoreScans<HexLattice>(scans, poses, options);
  MapConsistencyReport report;
  report.agreement = Summarize(scores);
  std::sort(scores.begin(), scores.end());
  report.low_quantile = SortedQuantile(scores, kLowQuantile);
  return report;
}

}  // namespace logs
}  // namespace hex_slam
