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
                const ScanMatcherOptions& options)
      : grid_(grid),
        scan_(scan),
        max_angle_step_(options.max_angle_step),
        max_translation_(options.max_translation_step_cells * grid.lattice().spacing()),
        translation_tolerance_(options.translation_tolerance_cells * grid.lattice().spacing()),
        angle_tolerance_(options.angle_tolerance) {}

  double Linearize(const State& pose, Equations* eq) const {
    LinearizeSquare(grid_, scan_, pose, eq);
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
};

}  // namespace

void LinearizeSquare(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                     const Eigen::Vector3d& pose, SquareNormalEquations* eq) {
  const double c = std::cos(pose[2]);
  const double s = std::sin(pose[2]);
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double cost = 0.0;
  double sum_value = 0.0;
  for (const Eigen::Vector2d& p : scan) {
    const Eigen::Vector2d rotated(c * p.x() - s * p.y(), s * p.x() + c * p.y());
    const SquareSample sample = InterpolateBilinear(grid, rotated + pose.head<2>());
    Eigen::Vector3d j;
    j << sample.gradient, sample.gradient.x() * -rotated.y() + sample.gradient.y() * rotated.x();
    const double r = 1.0 - sample.value;
    h.selfadjointView<Eigen::Upper>().rankUpdate(j);
    b += j * r;
    cost += r * r;
    sum_value += sample.value;
  }
  eq->hessian = h.selfadjointView<Eigen::Upper>();
  eq->gradient = b;
  eq->cost = cost;
  eq->sum_value = sum_value;
  eq->count = static_cast<int>(scan.size());
}

MatchResult SquareScanMatcher::Match(const MapPyramid<SquareLattice>& maps,
                                     const std::vector<Eigen::Vector2d>& points,
                                     const Pose2& guess) const {
  MatchResult result;
  result.levels.resize(maps.size());
  Eigen::Vector3d pose(guess.x, guess.y, guess.theta);
  SquareNormalEquations eq;
  std::vector<Eigen::Vector2d> scan;
  for (int level = maps.size() - 1; level >= 0; --level) {
    const SquareGrid& grid = maps.level(level);
    const bool finest = level == 0;
    DecimateScan(points, finest ? 0.0 : options_.coarse_point_spacing_cells * grid.lattice().spacing(),
                 &scan);
    SquareProblem problem(grid, scan, options_);
    LevelReport& report = result.levels[level];
    report.points = static_cast<int>(scan.size());
    pose = MinimizeLevel(problem, pose,
                         finest ? options_.max_iterations_fine : options_.max_iterations_coarse,
                         &eq, &report);
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
