#include "hex_slam/square_scan_matcher.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "gauss_newton.h"
#include "hex_slam/bilinear_interpolation.h"

namespace hex_slam {
namespace {

class SquareProblem {
 public:
  using State = Eigen::Vector3d;
  using Equations = SquareNormalEquations;

  SquareProblem(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                const ScanMatcherOptions& options, bool coarsest, bool subcell_offsets,
                double angle_tolerance)
      : grid_(grid),
        scan_(scan),
        max_angle_step_(options.max_angle_step),
        max_translation_(options.max_translation_step_cells * grid.lattice().spacing()),
        translation_tolerance_(options.translation_tolerance_cells * grid.lattice().spacing()),
        angle_tolerance_(angle_tolerance),
        robust_loss_scale_(options.LevelRobustLossScale(coarsest)),
        subcell_offsets_(subcell_offsets) {}

  double Linearize(const State& pose, Equations* eq) const {
    LinearizeSquare(grid_, scan_, pose, eq, subcell_offsets_, robust_loss_scale_);
    return eq->cost;
  }
  bool Solve(const Equations& eq, State* step) const {
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(eq.hessian);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
    *step = ldlt.solve(eq.gradient);
    return step->allFinite() && ldlt.vectorD().minCoeff() > 0.0;
  }
  State Apply(const State& pose, State step) const {
    const double t = step.head<2>().norm();
    if (t > max_translation_) step.head<2>() *= max_translation_ / t;
    step[2] = std::max(-max_angle_step_, std::min(max_angle_step_, step[2]));
    return pose + step;
  }
  bool Small(const State& step) const {
    return step.head<2>().norm() < translation_tolerance_ && std::abs(step[2]) < angle_tolerance_;
  }

 private:
  const SquareGrid& grid_;
  const std::vector<Eigen::Vector2d>& scan_;
  double max_angle_step_;
  double max_translation_;
  double translation_tolerance_;
  double angle_tolerance_;
  double robust_loss_scale_;
  bool subcell_offsets_;
};

// The loop of LinearizeSquare, compiled once per interpolation.
template <bool kSubcell>
void LinearizeSquareWith(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                         const Eigen::Vector3d& pose, const RobustKernel& kernel,
                         SquareNormalEquations* eq) {
  const double c = std::cos(pose[2]);
  const double s = std::sin(pose[2]);
  // The 6 distinct entries of the symmetric 3×3 Σ JᵀJ, accumulated as scalars.
  double h00 = 0, h01 = 0, h02 = 0, h11 = 0, h12 = 0, h22 = 0;
  double b0 = 0, b1 = 0, b2 = 0;
  double cost = 0.0;
  double sum_value = 0.0;
  for (const Eigen::Vector2d& p : scan) {
    const double rx = c * p.x() - s * p.y();
    const double ry = s * p.x() + c * p.y();
    const Eigen::Vector2d world(rx + pose.x(), ry + pose.y());
    const SquareSample sample =
        kSubcell ? InterpolateBilinearSubcell(grid, world) : InterpolateBilinear(grid, world);
    const double gx = sample.gradient.x(), gy = sample.gradient.y();
    const double j2 = -gx * ry + gy * rx;
    const double r = 1.0 - sample.value;
    const double w = kernel.Weight(r);
    const double wgx = w * gx, wgy = w * gy, wj2 = w * j2;
    h00 += wgx * gx, h01 += wgx * gy, h02 += wgx * j2;
    h11 += wgy * gy, h12 += wgy * j2;
    h22 += wj2 * j2;
    b0 += wgx * r, b1 += wgy * r, b2 += wj2 * r;
    cost += kernel.Cost(r);
    sum_value += sample.value;
  }
  eq->hessian << h00, h01, h02,
                 h01, h11, h12,
                 h02, h12, h22;
  eq->gradient << b0, b1, b2;
  eq->cost = cost;
  eq->sum_value = sum_value;
  eq->count = static_cast<int>(scan.size());
}

}  // namespace

void LinearizeSquare(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                     const Eigen::Vector3d& pose, SquareNormalEquations* eq, bool subcell_offsets,
                     double robust_loss_scale) {
  const RobustKernel kernel(robust_loss_scale);
  if (subcell_offsets) {
    LinearizeSquareWith<true>(grid, scan, pose, kernel, eq);
  } else {
    LinearizeSquareWith<false>(grid, scan, pose, kernel, eq);
  }
}

MatchResult SquareScanMatcher::Match(const MapPyramid<SquareLattice>& maps,
                                     const std::vector<Eigen::Vector2d>& points,
                                     const Pose2& guess) const {
  MatchResult result;
  result.levels.resize(maps.size());
  Eigen::Vector3d pose(guess.x, guess.y, guess.theta);
  SquareNormalEquations eq;
  const double reach = options_.coarsest_min_move_cells > 0.0 ? Reach(points) : 0.0;
  const double mean_range = MeanRange(points);
  for (int level = maps.size() - 1; level >= 0; --level) {
    const SquareGrid& grid = maps.level(level);
    const bool finest = level == 0;
    // The finest level matches every endpoint: no copy.
    if (!finest) {
      DecimateScan(points, options_.coarse_point_spacing_cells * grid.lattice().spacing(),
                   &decimated_);
    }
    const std::vector<Eigen::Vector2d>& scan = finest ? points : decimated_;
    // Sub-cell offsets on every level but the coarsest: there they would warp the smooth field
    // that level exists for and shrink the basin of convergence.
    const bool coarsest = level == maps.size() - 1 && maps.size() > 1;
    const double translation_tolerance =
        options_.translation_tolerance_cells * grid.lattice().spacing();
    SquareProblem problem(grid, scan, options_, coarsest, options_.subcell_offsets && !coarsest,
                          options_.LevelAngleTolerance(translation_tolerance, mean_range));
    LevelReport& report = result.levels[level];
    report.points = static_cast<int>(scan.size());
    const Eigen::Vector3d before = pose;
    pose = MinimizeLevel(problem, pose,
                         finest ? options_.max_iterations_fine : options_.max_iterations_coarse,
                         options_.verify_converged_step, &eq, &report);
    const double moved = EndpointMoveBound(Pose2(before.x(), before.y(), before.z()),
                                           Pose2(pose.x(), pose.y(), pose.z()), reach);
    if (coarsest && moved < options_.coarsest_min_move_cells * grid.lattice().spacing()) {
      pose = before;
      report.move_dropped = true;
    }
  }
  result.pose = Pose2(pose.x(), pose.y(), NormalizeAngle(pose.z()));
  result.hessian = eq.hessian;
  result.cost = eq.cost;
  result.num_points = eq.count;
  result.mean_occupancy = eq.count > 0 ? eq.sum_value / eq.count : 0.0;
  result.covariance = CovarianceFromHessian(eq.hessian, eq.cost, eq.count);
  return result;
}

}  // namespace hex_slam
