// Brute-force search of a pose window on one map level: the recovery step for scans whose
// Gauss–Newton match failed (a fast turn between 5 Hz scans, a wrong motion prediction).
// Gauss–Newton only converges from inside its basin (about a cell of the coarsest level and a
// few degrees); this looks everywhere in the window and hands the best pose back to it.
#ifndef HEX_SLAM_CORRELATIVE_SEARCH_H_
#define HEX_SLAM_CORRELATIVE_SEARCH_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/grid_map.h"
#include "hex_slam/pose2.h"

namespace hex_slam {

struct CorrelativeSearchOptions {
  double linear_window = 0.4;   // m, searched on each side of the centre in x and y
  double angular_window = 0.6;  // rad, searched on each side of the centre heading
  // Translation step in cells of the searched level; the angular step is chosen so that the
  // farthest endpoint moves by the same distance.
  double step_cells = 0.5;
  // Endpoints closer than this many cells to the previous kept one are merged.
  double point_spacing_cells = 1.0;

  std::vector<std::string> Validate() const;
};

struct CorrelativeResult {
  Pose2 pose;
  double score = 0.0;  // mean occupancy probability of the endpoints' cells at `pose`
  int candidates = 0;  // poses evaluated
};

// Scores every pose on a regular grid around `centre` by the mean probability of the cells the
// (decimated) endpoints fall in; returns the best.
template <class Lattice>
CorrelativeResult SearchCorrelative(const GridMap<Lattice>& grid,
                                    const std::vector<Eigen::Vector2d>& points,
                                    const Pose2& centre, const CorrelativeSearchOptions& options);

}  // namespace hex_slam

#endif  // HEX_SLAM_CORRELATIVE_SEARCH_H_
