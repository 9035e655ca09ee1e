// hector_mapping's matcher, the baseline: plain 3-DOF Gauss–Newton over (x, y, θ) with bilinear
// interpolation, coarse to fine over the square pyramid. Same options and result as the hex one.
#ifndef HEX_SLAM_MATCHING_SQUARE_SCAN_MATCHER_H_
#define HEX_SLAM_MATCHING_SQUARE_SCAN_MATCHER_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/map/square_grid.h"

namespace hex_slam {

using SquareNormalEquations = NormalEquations<3>;

// `scan`: endpoints in the robot frame; `pose` = (x, y, θ). `subcell_offsets`: read the map with
// InterpolateBilinearSubcell (ScanMatcherOptions::subcell_offsets). `robust_loss_scale`:
// ScanMatcherOptions::robust_loss_scale (H and b weighted, cost Σ ρ(r)).
void LinearizeSquare(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                     const Eigen::Vector3d& pose, SquareNormalEquations* eq,
                     bool subcell_offsets = false, double robust_loss_scale = 0.0);

// The square lattice's part of ScanMatcher: the state is the pose, endpoints as given.
template <>
struct ScanMatcherTraits<SquareLattice> {
  using Point = Eigen::Vector2d;
  using State = Eigen::Vector3d;
  using Equations = SquareNormalEquations;
  static Point ToPoint(const Eigen::Vector2d& p) { return p; }
  static State FromPose(const Pose2& pose) { return {pose.x, pose.y, pose.theta}; }
  static Pose2 ToPose(const State& pose) { return {pose.x(), pose.y(), NormalizeAngle(pose.z())}; }
  static void Linearize(const SquareGrid& grid, const std::vector<Point>& scan, const State& pose,
                        Equations* eq, bool subcell_offsets, double robust_loss_scale) {
    LinearizeSquare(grid, scan, pose, eq, subcell_offsets, robust_loss_scale);
  }
  static bool Solve(const Equations& eq, State* step);  // H Δ = b by LDLT
  static double TranslationLength(const State& step) { return step.head<2>().norm(); }
  static State Add(const State& pose, const State& step) { return pose + step; }
  static Eigen::Matrix3d PoseHessian(const Eigen::Matrix3d& hessian) { return hessian; }
};

extern template class ScanMatcher<SquareLattice>;
using SquareScanMatcher = ScanMatcher<SquareLattice>;

}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_SQUARE_SCAN_MATCHER_H_
