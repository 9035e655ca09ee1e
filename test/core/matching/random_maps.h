// Random occupancy maps and scans for the matching tests: a map from random scans at random
// origins (free, occupied and never-seen cells mixed as mapping leaves them), and random points.
#ifndef HEX_SLAM_TEST_CORE_MATCHING_RANDOM_MAPS_H_
#define HEX_SLAM_TEST_CORE_MATCHING_RANDOM_MAPS_H_

#include <random>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/matching/lattice_axes.h"
#include "hex_slam/matching/precomputation_grid.h"

namespace hex_slam {
namespace testing_util {

template <class Lattice>
GridMap<Lattice> RandomMap(double spacing, std::mt19937_64* rng) {
  GridMap<Lattice> grid(Lattice(spacing), OccupancyModel::FromFactors(0.4, 0.9, 50.0),
                        GridGrowthPolicy(),
                        Eigen::AlignedBox2d(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2)));
  std::uniform_real_distribution<double> origin(-1.5, 1.5), angle(-M_PI, M_PI), range(0.2, 2.5);
  std::uniform_int_distribution<int> scans(3, 12), endpoints(5, 80);
  const int n = scans(*rng);
  for (int s = 0; s < n; ++s) {
    const Eigen::Vector2d o(origin(*rng), origin(*rng));
    std::vector<Eigen::Vector2d> points;
    const int m = endpoints(*rng);
    for (int i = 0; i < m; ++i) {
      const double a = angle(*rng), r = range(*rng);
      points.push_back(o + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    grid.InsertScan(o, points);
  }
  return grid;
}

inline std::vector<Eigen::Vector2d> RandomPoints(int count, double max_range, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), range(0.1, max_range);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < count; ++i) {
    const double a = angle(*rng), r = range(*rng);
    points.push_back(r * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return points;
}

// What the matcher's cells hold, read through the map's own accessors and stored as the grids
// store values (QuantizedProbability).
template <class Lattice>
double CellValue(const GridMap<Lattice>& grid, const Eigen::Array2i& z, double unknown) {
  const GridIndex index = Lattice::ToIndex(matching::LatticeAxes<Lattice>::CellAt(z));
  return matching::QuantizedProbability(grid.IsKnownAt(index) ? grid.ProbabilityAt(index)
                                                              : static_cast<float>(unknown));
}

}  // namespace testing_util
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_CORE_MATCHING_RANDOM_MAPS_H_
