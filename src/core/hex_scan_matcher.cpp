#include "hex_slam/hex_scan_matcher.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

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

  double Linearize(const State& xi, Equations* eq) const {
    LinearizeHex(grid_, scan_, xi, eq, subcell_offsets_, robust_loss_scale_);
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
  double robust_loss_scale_;
  bool subcell_offsets_;
};

// Points are read in blocks: with sub-cell offsets, a first pass finds every point's offset and
// a second reads the plain map at the moved points. In one pass each point's two dependent
// reads form a chain too long for the processor to overlap with the next point's (22 against 32
// ns per point on the simulated room drive); the block keeps the moved points in registers' reach.
constexpr int kPointBlock = 64;

// The loop of LinearizeHex, compiled once per interpolation so the choice costs nothing per point.
template <bool kSubcell>
void LinearizeHexWith(const HexGrid& grid, const std::vector<Eigen::Vector3d>& scan,
                      const Eigen::Vector4d& xi, const RobustKernel& kernel,
                      HexNormalEquations* eq) {
  // Work in lattice units (cube metres / w): scan and translation scaled once here, H and b
  // rescaled once at the end, so the loop has no per-point scaling. Only x and y of each rotated
  // point are computed; ζ = -x - y. Rows of R(ψ) acting on (x, y, -x-y) fold into 2×2.
  const double inv_w = grid.lattice().inv_cube_scale();
  const Eigen::Matrix3d r = CubeRotation(xi[3]) * inv_w;
  const double r00 = r(0, 0) - r(0, 2), r01 = r(0, 1) - r(0, 2);
  const double r10 = r(1, 0) - r(1, 2), r11 = r(1, 1) - r(1, 2);
  const double px = xi[0] * inv_w, py = xi[1] * inv_w;
  // The map is read as partials d = (∂M/∂u_x, ∂M/∂u_y) (HexPartials). The in-plane gradient is
  // g = ((2 d_x - d_y) / 3, (2 d_y - d_x) / 3, -(d_x + d_y) / 3), and with v = R s and
  // ∂S/∂ψ = n × v, n = (1,1,1)/sqrt(3) (the rotation's derivative about its own axis, equal to
  // MATH.md §5's expression), the in-plane algebra gives g·(n × v) = sqrt(3)·(g_y v_x - g_x v_y)
  // = sqrt(3)·(d_y e_x - d_x e_y) with e = ((2 v_x + v_y) / 3, (v_x + 2 v_y) / 3): the rows of
  // R for e fold the same way, so a point costs no more in partials than in g.
  const double e00 = (2.0 * r00 + r10) / 3.0, e01 = (2.0 * r01 + r11) / 3.0;
  const double e10 = (r00 + 2.0 * r10) / 3.0, e11 = (r01 + 2.0 * r11) / 3.0;

  // Sums in partials: of the paper's 4×4 H = Σ JᵀJ with J = (g_x, g_y, g_ζ, g·∂S/∂ψ) only six
  // are independent, and of b three; the rest follow exactly after the loop.
  double sxx = 0, sxy = 0, syy = 0, sxr = 0, syr = 0, srr = 0;
  double bx = 0, by = 0, br = 0;
  double cost = 0.0;
  double sum_value = 0.0;
  double moved_x[kPointBlock], moved_y[kPointBlock];
  for (std::size_t start = 0; start < scan.size(); start += kPointBlock) {
    const int n = static_cast<int>(std::min<std::size_t>(kPointBlock, scan.size() - start));
    const Eigen::Vector3d* block = scan.data() + start;
    for (int i = 0; i < n; ++i) {
      const double ux = r00 * block[i].x() + r01 * block[i].y() + px;
      const double uy = r10 * block[i].x() + r11 * block[i].y() + py;
      double ox = 0.0, oy = 0.0;
      if (kSubcell) HexHitOffset(grid, ux, uy, &ox, &oy);
      moved_x[i] = ux - ox;
      moved_y[i] = uy - oy;
    }
    for (int i = 0; i < n; ++i) {
      const HexPartials m = InterpolateHexPartials(grid, moved_x[i], moved_y[i]);
      const double ex = e00 * block[i].x() + e01 * block[i].y();
      const double ey = e10 * block[i].x() + e11 * block[i].y();
      const double dx = m.du_x, dy = m.du_y;
      const double jr = dy * ex - dx * ey;
      const double res = 1.0 - m.value;
      const double w = kernel.Weight(res);
      const double wdx = w * dx, wdy = w * dy, wjr = w * jr;
      sxx += wdx * dx, sxy += wdx * dy, syy += wdy * dy;
      sxr += wdx * jr, syr += wdy * jr, srr += wjr * jr;
      bx += wdx * res, by += wdy * res, br += wjr * res;
      cost += kernel.Cost(res);
      sum_value += m.value;
    }
  }
  // From partials to the in-plane gradient's sums (g_x = (2 d_x - d_y) / 3, ...), and back to
  // metres: the gradient per metre is g/w; v was in lattice units, so g·(n × v) per radian is
  // sqrt(3)·jr exactly as accumulated (the w's cancel).
  const double gxx = (4.0 * sxx - 4.0 * sxy + syy) / 9.0;
  const double gxy = (5.0 * sxy - 2.0 * sxx - 2.0 * syy) / 9.0;
  const double gyy = (4.0 * syy - 4.0 * sxy + sxx) / 9.0;
  const double gxr = (2.0 * sxr - syr) / 3.0, gyr = (2.0 * syr - sxr) / 3.0;
  const double gbx = (2.0 * bx - by) / 3.0, gby = (2.0 * by - bx) / 3.0;
  const double tp = inv_w;
  const double tr = kSqrt3;
  const double h00 = gxx * tp * tp, h01 = gxy * tp * tp, h11 = gyy * tp * tp;
  const double h03 = gxr * tp * tr, h13 = gyr * tp * tr, h33 = srr * tr * tr;
  const double h02 = -h00 - h01, h12 = -h01 - h11, h22 = h00 + 2.0 * h01 + h11;
  const double h23 = -h03 - h13;
  eq->hessian << h00, h01, h02, h03,
                 h01, h11, h12, h13,
                 h02, h12, h22, h23,
                 h03, h13, h23, h33;
  const double b0 = gbx * tp, b1 = gby * tp;
  eq->gradient << b0, b1, -b0 - b1, br * tr;
  eq->cost = cost;
  eq->sum_value = sum_value;
  eq->count = static_cast<int>(scan.size());
}

}  // namespace

void LinearizeHex(const HexGrid& grid, const std::vector<Eigen::Vector3d>& scan,
                  const Eigen::Vector4d& xi, HexNormalEquations* eq, bool subcell_offsets,
                  double robust_loss_scale) {
  const RobustKernel kernel(robust_loss_scale);
  if (subcell_offsets) {
    LinearizeHexWith<true>(grid, scan, xi, kernel, eq);
  } else {
    LinearizeHexWith<false>(grid, scan, xi, kernel, eq);
  }
}

bool SolveLagrangeStep(const Eigen::Matrix4d& hessian, const Eigen::Vector4d& gradient,
                       Eigen::Vector4d* step) {
  // The null-space method: the steps with n·Δξ = 0 are Δξ = A y, A = CubePoseJacobian(), so the
  // first block row projected on the plane, AᵀHA y = Aᵀb, is the whole system (Aᵀn = 0 removes
  // λ), and it is nonsingular exactly when the 5×5 one is. A 3×3 LDLT instead of a 5×5
  // full-pivot LU: a few hundred operations less per iteration.
  const Eigen::Matrix<double, 4, 3> a = CubePoseJacobian();
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(a.transpose() * hessian * a);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().minCoeff() > 0.0)) {
    return false;
  }
  const Eigen::Vector4d solution = a * ldlt.solve(a.transpose() * gradient);
  if (!solution.allFinite()) return false;
  *step = solution;
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
  std::vector<Eigen::Vector3d>& scan = scan_;
  const double reach = options_.coarsest_min_move_cells > 0.0 ? Reach(points) : 0.0;
  const double mean_range = MeanRange(points);
  for (int level = maps.size() - 1; level >= 0; --level) {
    const HexGrid& grid = maps.level(level);
    const bool finest = level == 0;
    scan.clear();
    ForEachKeptEndpoint(
        points, finest ? 0.0 : options_.coarse_point_spacing_cells * grid.lattice().spacing(),
        [&scan](const Eigen::Vector2d& p) { scan.push_back(CartesianToCube(p.x(), p.y())); });
    // Sub-cell offsets on every level but the coarsest: there they would warp the smooth field
    // that level exists for and shrink the basin of convergence.
    const bool coarsest = level == maps.size() - 1 && maps.size() > 1;
    const double translation_tolerance =
        options_.translation_tolerance_cells * grid.lattice().spacing();
    HexProblem problem(grid, scan, options_, coarsest, options_.subcell_offsets && !coarsest,
                       options_.LevelAngleTolerance(translation_tolerance, mean_range));
    LevelReport& report = result.levels[level];
    report.points = static_cast<int>(scan.size());
    const Eigen::Vector4d before = xi;
    xi = MinimizeLevel(problem, xi,
                       finest ? options_.max_iterations_fine : options_.max_iterations_coarse,
                       options_.verify_converged_step, &eq, &report);
    const double moved = EndpointMoveBound(PoseFromCubeState(before), PoseFromCubeState(xi), reach);
    if (coarsest && moved < options_.coarsest_min_move_cells * grid.lattice().spacing()) {
      xi = before;
      report.move_dropped = true;
    }
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
