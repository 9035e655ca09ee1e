// Branch-and-bound correlative scan matching (Olson 2009, as Cartographer's fast correlative scan
// matcher), written once over the lattice: in lattice coordinates (LatticeAxes) every lattice is
// Z², so sliding a scan by whole cells adds an integer offset to every endpoint's cell, and a
// block of 2^k × 2^k offsets (on the hex lattice an axial parallelogram) is bounded by one read
// per endpoint of the depth-k precomputation grid. The score of a pose is the mean cell value
// (occupancy probability; unknown cells count as `unknown_probability`) of the endpoints' cells;
// the search returns the best pose of the discretised window, exactly as an exhaustive search of
// the same window would, touching a small fraction of it.
//
// Used for loop closure: a node's scan against a finished submap, around the pose the pose graph
// expects (Match) or anywhere on it (MatchFullSubmap). The result is a cell-and-angle-step
// estimate for Gauss–Newton to refine.
#ifndef HEX_SLAM_MATCHING_FAST_CORRELATIVE_SCAN_MATCHER_H_
#define HEX_SLAM_MATCHING_FAST_CORRELATIVE_SCAN_MATCHER_H_

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/matching/precomputation_grid.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace matching {

// Cartographer's names and meanings.
struct FastCorrelativeScanMatcherOptions {
  // m, searched on each side of the initial pose in x and y: Cartographer's 7 m. At 3 m, MIT
  // Killian's front end, 4-22 m off over the 2000 s between two visits of one stretch, left that
  // loop open in four of five runs with the map-update thresholds nudged (docs/real_logs.md,
  // stop 46).
  double linear_search_window = 7.0;
  double angular_search_window = 0.5236;  // rad (30°), on each side of the initial heading
  // Precomputed depths 0 .. depth - 1: the coarsest bound covers 2^(depth-1) cells per side.
  int branch_and_bound_depth = 7;
  // What an endpoint in a never-observed cell scores: low, so a scan pushed off the map does not
  // look like a match, but above free space (Cartographer's unknown cells score its minimum
  // probability, 0.1).
  double unknown_probability = 0.1;
  // Ambiguity: after the best pose, the best one outside its peak (farther than peak_radius in
  // either lattice axis' direction or peak_angle in heading) is looked for; it is reported when
  // it scores at least ambiguity_ratio of the best (a maze's or a corridor's repeats). 0: no
  // such search. Two copies of a room seen from the same place score alike only up to the cells'
  // phase: 0.87-0.93 of each other on the hex lattice (0.99 on the square one, whose spacing
  // divided the rooms' distance), hence 0.85. The rival counts even when it scores below the
  // search's min_score: a match that only just passes is no less ambiguous for it.
  double ambiguity_ratio = 0.85;
  double peak_radius = 0.5;  // m
  double peak_angle = 0.35;  // rad (20°)

  // Empty when valid; otherwise one message per bad field, naming it.
  std::vector<std::string> Validate() const;
};

struct CorrelativeMatch {
  Pose2 pose;          // of the robot, in the grid's frame
  double score = 0.0;  // mean cell value at the endpoints
  // The best score outside the best pose's peak when it reaches ambiguity_ratio·score (another
  // place the scan fits about as well, whether or not it reaches min_score); 0 otherwise.
  double runner_up_score = 0.0;
  Pose2 runner_up_pose;  // where it scored runner_up_score (when that is not 0)
  long candidates = 0;  // bounds and poses scored
};

// One rotation of the scan: its endpoints' cells in lattice coordinates with the window's centre
// translation applied, and the offsets still worth searching for it.
struct DiscreteScan {
  double theta = 0.0;  // heading of this rotation (rad, not normalised)
  std::vector<Eigen::Array2i> cells;
  Eigen::Array2i min_offset = Eigen::Array2i::Zero();
  Eigen::Array2i max_offset = Eigen::Array2i::Zero();
  // The box of `cells` (set by the search before it scores).
  Eigen::Array2i lowest = Eigen::Array2i::Zero();
  Eigen::Array2i highest = Eigen::Array2i::Zero();
};

// The angular step that moves the farthest of `points` by about one cell: acos(1 - d²/(2r²)).
double AngularSearchStep(double spacing, const std::vector<Eigen::Vector2d>& points);

// The scan turned to centre.theta + i·step for i in [-half_count, half_count], moved to the
// centre's translation and discretised; every rotation gets the offsets [min, max].
template <class Lattice>
std::vector<DiscreteScan> DiscretizeScans(const Lattice& lattice, const Pose2& centre,
                                          const std::vector<Eigen::Vector2d>& points, double step,
                                          int half_count, const Eigen::Array2i& min_offset,
                                          const Eigen::Array2i& max_offset);

template <class Lattice>
class FastCorrelativeScanMatcher {
 public:
  // Precomputes the grids of `grid` (which is not referenced afterwards).
  FastCorrelativeScanMatcher(const GridMap<Lattice>& grid,
                             const FastCorrelativeScanMatcherOptions& options);

  // The best pose within the windows around `initial_pose` (the robot in the grid's frame) for
  // `points` (robot frame), if it scores above `min_score`.
  std::optional<CorrelativeMatch> Match(const Pose2& initial_pose,
                                        const std::vector<Eigen::Vector2d>& points,
                                        double min_score) const;
  // The same with `linear_window` (m) and `angular_window` (rad) instead of the options'.
  std::optional<CorrelativeMatch> Match(const Pose2& initial_pose,
                                        const std::vector<Eigen::Vector2d>& points,
                                        double min_score, double linear_window,
                                        double angular_window) const;
  // The same over every pose that puts part of the scan on the map, at every heading.
  std::optional<CorrelativeMatch> MatchFullSubmap(const std::vector<Eigen::Vector2d>& points,
                                                  double min_score) const;

  // The window Match searches around `initial_pose` (±linear_window m, ±angular_window rad),
  // discretised (before it is cut to the map).
  std::vector<DiscreteScan> Window(const Pose2& initial_pose,
                                   const std::vector<Eigen::Vector2d>& points,
                                   double linear_window, double angular_window) const;

  const Lattice& lattice() const { return lattice_; }
  const FastCorrelativeScanMatcherOptions& options() const { return options_; }
  const PrecomputationGridStack& grids() const { return grids_; }
  std::size_t MemoryBytes() const { return grids_.MemoryBytes(); }

 private:
  std::optional<CorrelativeMatch> Search(std::vector<DiscreteScan> scans, const Pose2& centre,
                                         double min_score) const;
  // The peak's half-width in lattice offsets.
  int PeakCells() const;

  Lattice lattice_;
  Eigen::Matrix2d basis_;
  FastCorrelativeScanMatcherOptions options_;
  PrecomputationGridStack grids_;
};

}  // namespace matching
}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_FAST_CORRELATIVE_SCAN_MATCHER_H_
