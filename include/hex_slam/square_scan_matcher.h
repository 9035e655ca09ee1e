// hector_mapping's matcher, the baseline: plain 3-DOF Gauss–Newton over (x, y, θ) with bilinear
// interpolation, coarse to fine over the square pyramid. Same options and result as the hex one.
#ifndef HEX_SLAM_SQUARE_SCAN_MATCHER_H_
#define HEX_SLAM_SQUARE_SCAN_MATCHER_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/map_pyramid.h"
#include "hex_slam/scan_matcher.h"
#include "hex_slam/square_grid.h"

namespace hex_slam {

struct SquareNormalEquations {
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  double cost = 0.0;
  double sum_value = 0.0;
  int count = 0;
};

// `scan`: endpoints in the robot frame; `pose` = (x, y, θ). `subcell_offsets`: read the map with
// InterpolateBilinearSubcell (ScanMatcherOptions::subcell_offsets). `robust_loss_scale`:
// ScanMatcherOptions::robust_loss_scale (H and b weighted, cost Σ ρ(r)).
void LinearizeSquare(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                     const Eigen::Vector3d& pose, SquareNormalEquations* eq,
                     bool subcell_offsets = false, double robust_loss_scale = 0.0);

class SquareScanMatcher {
 public:
  explicit SquareScanMatcher(const ScanMatcherOptions& options) : options_(options) {}

  MatchResult Match(const MapPyramid<SquareLattice>& maps,
                    const std::vector<Eigen::Vector2d>& points, const Pose2& guess) const;

 private:
  ScanMatcherOptions options_;
  // A coarse level's decimated endpoints; scratch kept between calls to save allocations.
  mutable std::vector<Eigen::Vector2d> decimated_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_SQUARE_SCAN_MATCHER_H_
