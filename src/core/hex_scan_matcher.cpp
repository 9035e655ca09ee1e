#include "hex_slam/hex_scan_matcher.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "gauss_newton.h"
#include "hex_slam/cube.h"
#include "hex_slam/hex_interpolation.h"

namespace hex_slam {
namespace {

class HexProblem {
 public:
  using State = Eigen::Vector4d;
  using Equations = HexNormalEquations;

  HexProblem(const HexGrid& grid, const std::vector<Eigen::Vector3d>& scan,
             const ScanMatcherOptions& options)
      : grid_(grid),
        scan_(scan),
        max_angle_step_(options.max_angle_step),
        max_translation_(options.max_translation_step_cells * grid.lattice().spacing()),
        translation_tolerance_(options.translation_tolerance_cells * grid.lattice().spacing()),
        angle_tolerance_(options.angle_tolerance) {}

  double Linearize(const State& xi, Equations* eq) const {
    LinearizeHex(grid_, scan_, xi, eq);
    return eq->cost;
  }
  bool Solve(const Equations& eq, State* step) const {
    return SolveLagrangeStep(eq.hessian, eq.gradient, step);
  }
  State Apply(const State& xi, State step) const {
    const double t = CartesianLength(step);
    if (t > max_translation_) step.head<3>() *= max_translation_ / t;
    step[3] = std::max(-max_angle_step_, std::min(max_angle_step_, step[3]));
    State next = xi + step;
    // Re-project onto the plane so rounding never accumulates off it.
    next.head<3>().array() -= next.head<3>().sum() / 3.0;
    return next;
  }
  bool Small(const State& step) const {
    return CartesianLength(step) < translation_tolerance_ && std::abs(step[3]) < angle_tolerance_;
  }

 private:
  static double CartesianLength(const State& step) {
    return CubeToCartesian(step.head<3>()).norm();
  }

  const HexGrid& grid_;
  const std::vector<Eigen::Vector3d>& scan_;
  double max_angle_step_;
  double max_translation_;
  double translation_tolerance_;
  double angle_tolerance_;
};

}  // namespace

void LinearizeHex(const HexGrid& grid, const std::vector<Eigen::Vector3d>& scan,
                  const Eigen::Vector4d& xi, HexNormalEquations* eq) {
  const Eigen::Matrix3d rotation = CubeRotation(xi[3]);
  const Eigen::Vector3d p = xi.head<3>();
  const double sn = std::sin(xi[3]);
  const double cs = std::cos(xi[3]) / kSqrt3;
  Eigen::Matrix4d h = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  double cost = 0.0;
  double sum_value = 0.0;
  for (const Eigen::Vector3d& s : scan) {
    const HexSample sample = InterpolateHex(grid, rotation * s + p);
    // ∂S/∂ψ written out (MATH.md §5) rather than through CubeRotationDerivative, to reuse sin/cos.
    const Eigen::Vector3d ds(-s.x() * sn + (s.z() - s.y()) * cs,
                             -s.y() * sn + (s.x() - s.z()) * cs,
                             -s.z() * sn + (s.y() - s.x()) * cs);
    Eigen::Vector4d j;
    j << sample.gradient, sample.gradient.dot(ds);
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

bool SolveLagrangeStep(const Eigen::Matrix4d& hessian, const Eigen::Vector4d& gradient,
                       Eigen::Vector4d* step) {
  Eigen::Matrix<double, 5, 5> kkt = Eigen::Matrix<double, 5, 5>::Zero();
  kkt.topLeftCorner<4, 4>() = hessian;
  kkt(0, 4) = kkt(1, 4) = kkt(2, 4) = 0.5;
  kkt(4, 0) = kkt(4, 1) = kkt(4, 2) = 1.0;
  Eigen::Matrix<double, 5, 1> rhs;
  rhs << gradient, 0.0;
  const Eigen::FullPivLU<Eigen::Matrix<double, 5, 5>> lu(kkt);
  if (!lu.isInvertible()) return false;
  const Eigen::Matrix<double, 5, 1> solution = lu.solve(rhs);
  if (!solution.allFinite()) return false;
  *step = solution.head<4>();
  return true;
}

Eigen::Matrix<double, 4, 3> CubePoseJacobian() {
  Eigen::Matrix<double, 4, 3> a;
  a << 1.0, 0.0, 0.0,
       -0.5, 0.5 * kSqrt3, 0.0,
       -0.5, -0.5 * kSqrt3, 0.0,
       0.0, 0.0, 1.0;
  return a;
}

Eigen::Vector4d CubeStateFromPose(const Pose2& pose) {
  Eigen::Vector4d xi;
  xi << CartesianToCube(pose.x, pose.y), pose.theta;
  return xi;
}

Pose2 PoseFromCubeState(const Eigen::Vector4d& xi) {
  const Eigen::Vector2d t = CubeToCartesian(xi.head<3>());
  return {t.x(), t.y(), NormalizeAngle(xi[3])};
}

MatchResult HexScanMatcher::Match(const MapPyramid<HexLattice>& maps,
                                  const std::vector<Eigen::Vector2d>& points,
                                  const Pose2& guess) const {
  MatchResult result;
  result.levels.resize(maps.size());
  Eigen::Vector4d xi = CubeStateFromPose(guess);
  HexNormalEquations eq;
  std::vector<Eigen::Vector2d> kept;
  std::vector<Eigen::Vector3d> scan;
  for (int level = maps.size() - 1; level >= 0; --level) {
    const HexGrid& grid = maps.level(level);
    const bool finest = level == 0;
    DecimateScan(points, finest ? 0.0 : options_.coarse_point_spacing_cells * grid.lattice().spacing(),
                 &kept);
    scan.clear();
    for (const Eigen::Vector2d& p : kept) scan.push_back(CartesianToCube(p.x(), p.y()));
    HexProblem problem(grid, scan, options_);
    LevelReport& report = result.levels[level];
    report.points = static_cast<int>(scan.size());
    xi = MinimizeLevel(problem, xi,
                       finest ? options_.max_iterations_fine : options_.max_iterations_coarse,
                       &eq, &report);
  }
  result.pose = PoseFromCubeState(xi);
  const Eigen::Matrix<double, 4, 3> a = CubePoseJacobian();
  result.hessian = a.transpose() * eq.hessian * a;
  result.cost = eq.cost;
  result.num_points = eq.count;
  result.mean_occupancy = eq.count > 0 ? eq.sum_value / eq.count : 0.0;
  result.covariance = CovarianceFromHessian(result.hessian, eq.cost, eq.count);
  return result;
}

}  // namespace hex_slam
