// The paper's matcher (MATH.md §6): Gauss–Newton in cube coordinates over ξ = (p_x, p_y, p_ζ, ψ)
// with the Lagrange constraint p_x + p_y + p_ζ = 0, coarse to fine over the hex pyramid.
#ifndef HEX_SLAM_MATCHING_HEX_SCAN_MATCHER_H_
#define HEX_SLAM_MATCHING_HEX_SCAN_MATCHER_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/cube.h"
#include "hex_slam/map/hex_grid.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/matching/scan_matcher.h"

namespace hex_slam {

// Σ J_iᵀJ_i, Σ J_iᵀr_i and Σ r_i² at one ξ, with r_i = 1 - M(S_i(ξ)).
using HexNormalEquations = NormalEquations<4>;

// `scan` holds endpoints in cube coordinates (metres) of the robot frame. `subcell_offsets`: read
// the map with InterpolateHexSubcell (ScanMatcherOptions::subcell_offsets). `robust_loss_scale`:
// ScanMatcherOptions::robust_loss_scale (H and b weighted, cost Σ ρ(r)).
void LinearizeHex(const HexGrid& grid, const std::vector<Eigen::Vector3d>& scan,
                  const Eigen::Vector4d& xi, HexNormalEquations* eq,
                  bool subcell_offsets = false, double robust_loss_scale = 0.0);

// Solves the 5×5 system [H n/2; nᵀ 0][Δξ; λ] = [b; 0], n = (1, 1, 1, 0), by its null space (the
// reduced 3×3 system on the plane p_x + p_y + p_ζ = 0). False when it is singular.
bool SolveLagrangeStep(const Eigen::Matrix4d& hessian, const Eigen::Vector4d& gradient,
                       Eigen::Vector4d* step);

// ∂(p_x, p_y, p_ζ, ψ)/∂(x, y, θ): maps a Cartesian pose change into cube space.
Eigen::Matrix<double, 4, 3> CubePoseJacobian();

Eigen::Vector4d CubeStateFromPose(const Pose2& pose);
Pose2 PoseFromCubeState(const Eigen::Vector4d& xi);

// The hex lattice's part of ScanMatcher: the state ξ, endpoints in cube coordinates. Defined
// here, inline, as they are called per endpoint and per step.
template <>
struct ScanMatcherTraits<HexLattice> {
  using Point = Eigen::Vector3d;
  using State = Eigen::Vector4d;
  using Equations = HexNormalEquations;
  static Point ToPoint(const Eigen::Vector2d& p) { return CartesianToCube(p.x(), p.y()); }
  static State FromPose(const Pose2& pose) { return CubeStateFromPose(pose); }
  static Pose2 ToPose(const State& xi) { return PoseFromCubeState(xi); }
  static void Linearize(const HexGrid& grid, const std::vector<Point>& scan, const State& xi,
                        Equations* eq, bool subcell_offsets, double robust_loss_scale) {
    LinearizeHex(grid, scan, xi, eq, subcell_offsets, robust_loss_scale);
  }
  static bool Solve(const Equations& eq, State* step) {
    return SolveLagrangeStep(eq.hessian, eq.gradient, step);
  }
  static double TranslationLength(const State& step) {
    return CubeToCartesian(step.head<3>()).norm();
  }
  // ξ + Δξ, re-projected onto the plane so rounding never accumulates off it.
  static State Add(const State& xi, const State& step) {
    State next = xi + step;
    next.head<3>().array() -= next.head<3>().sum() / 3.0;
    return next;
  }
  static Eigen::Matrix3d PoseHessian(const Eigen::Matrix4d& hessian) {
    const Eigen::Matrix<double, 4, 3> a = CubePoseJacobian();
    return a.transpose() * hessian * a;
  }
};

extern template class ScanMatcher<HexLattice>;
using HexScanMatcher = ScanMatcher<HexLattice>;

}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_HEX_SCAN_MATCHER_H_
