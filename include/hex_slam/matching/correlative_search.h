// Exhaustive search of a pose window on one map level: the recovery step for scans whose
// Gauss–Newton match failed (a fast turn between 5 Hz scans, a wrong motion prediction).
// Gauss–Newton only converges from inside its basin (about a cell of the coarsest level and a
// few degrees); this looks everywhere in the window and hands the best pose back to it. A large
// window is searched by branch and bound over bounds one translation step wide
// (matching/step_bounds.h): the same pose as scoring every one, 7-17 times sooner on hex cells
// (hex_slam_matching_bench).
#ifndef HEX_SLAM_MATCHING_CORRELATIVE_SEARCH_H_
#define HEX_SLAM_MATCHING_CORRELATIVE_SEARCH_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {

struct CorrelativeSearchOptions {
  double linear_window = 0.4;   // m, searched on each side of the centre in x and y
  double angular_window = 0.6;  // rad, searched on each side of the centre heading
  // Translation step in cells of the searched level; the angular step is chosen so that the
  // farthest endpoint moves by the same distance.
  double step_cells = 0.5;
  // Endpoints closer than this many cells to the previous kept one are merged.
  double point_spacing_cells = 1.0;
  // The most poses one search may score. The default window takes ~5,000; a window whose grid
  // would take more (a wide window on a fine level, a scan whose endpoints lie kilometres from
  // the base) is refused rather than run for minutes.
  int max_candidates = 200000;
  // A window over max_candidates is searched with its steps made coarser, by up to this factor,
  // until it fits; beyond that it is refused. 1: refused at once.
  double max_step_coarsening = 1.0;
  // Large windows are searched by branch and bound (the same result as scoring every pose, far
  // sooner); false scores every pose, to compare the two.
  bool branch_and_bound = true;

  std::vector<std::string> Validate() const;
};

// The finest angular step the search takes (rad): a translation step of 0.1 m (the default on
// 0.2 m cells) at 100 m. Endpoints farther from the base than that (a mounting kilometres off, a
// bad calibration) would otherwise shrink the step towards nothing and multiply the poses.
constexpr double kMinCorrelativeAngularStep = 1e-3;

struct CorrelativeResult {
  Pose2 pose;
  double score = 0.0;  // mean occupancy probability of the endpoints' cells at `pose`
  // Poses in the window: each was scored, or ruled out by a bound on a block of poses.
  int candidates = 0;
  double step_coarsening = 1.0;  // how much coarser than asked the steps were, to fit the budget
  double linear_step = 0.0, angular_step = 0.0;  // the window's steps (m, rad) as searched
  // The window was searched by branch and bound (large enough to pay for its bounds), not pose
  // by pose; the result is the same. (Nor either when no endpoint can reach a written cell:
  // every pose ties with the centre.)
  bool branch_and_bound = false;
  // Empty when the search ran; otherwise why it did not (its grid exceeds max_candidates), and
  // `pose` is the centre.
  std::string refused;
};

// The best pose on a regular grid around `centre` by the mean probability of the cells the
// (decimated) endpoints fall in: the highest score; among equal scores the fewest steps from the
// centre, then the first in heading, x, y order. The angular step moves most endpoints by about
// one translation step, but is never finer than kMinCorrelativeAngularStep.
template <class Lattice>
CorrelativeResult SearchCorrelative(const GridMap<Lattice>& grid,
                                    const std::vector<Eigen::Vector2d>& points,
                                    const Pose2& centre, const CorrelativeSearchOptions& options);

// The score SearchCorrelative gives `pose`: the mean probability of the cells the decimated
// endpoints fall in (0 for no endpoints). Comparing two poses by it compares them as the search
// would, whatever window they came from.
template <class Lattice>
double CorrelativeScore(const GridMap<Lattice>& grid, const std::vector<Eigen::Vector2d>& points,
                        const Pose2& pose, const CorrelativeSearchOptions& options);

}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_CORRELATIVE_SEARCH_H_
