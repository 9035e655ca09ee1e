#include "hex_slam/matching/hex_scan_matcher.h"

#include <algorithm>
#include <cmath>

#include "matching/gauss_newton.h"
#include "hex_slam/geometry/cube.h"
#include "hex_slam/map/hex_interpolation.h"

namespace hex_slam {
namespace {

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

  // Sums in partials, J = (d_x, d_y, jr) with jr = d_y e_x - d_x e_y: of the paper's 4×4 H = Σ JᵀJ with
  // J = (g_x, g_y, g_ζ, g·∂S/∂ψ) only six are independent, and of b three; the rest follow
  // exactly after the loop.
  NormalSums s;
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
      s.Add(kernel, m.value, m.du_x, m.du_y, m.du_y * ex - m.du_x * ey);
    }
  }
  // From partials to the in-plane gradient's sums (g_x = (2 d_x - d_y) / 3, ...), and back to
  // metres: the gradient per metre is g/w; v was in lattice units, so g·(n × v) per radian is
  // sqrt(3)·jr exactly as accumulated (the w's cancel).
  const double gxx = (4.0 * s.h00 - 4.0 * s.h01 + s.h11) / 9.0;
  const double gxy = (5.0 * s.h01 - 2.0 * s.h00 - 2.0 * s.h11) / 9.0;
  const double gyy = (4.0 * s.h11 - 4.0 * s.h01 + s.h00) / 9.0;
  const double gxr = (2.0 * s.h02 - s.h12) / 3.0, gyr = (2.0 * s.h12 - s.h02) / 3.0;
  const double gbx = (2.0 * s.b0 - s.b1) / 3.0, gby = (2.0 * s.b1 - s.b0) / 3.0;
  const double tp = inv_w;
  const double tr = kSqrt3;
  const double h00 = gxx * tp * tp, h01 = gxy * tp * tp, h11 = gyy * tp * tp;
  const double h03 = gxr * tp * tr, h13 = gyr * tp * tr, h33 = s.h22 * tr * tr;
  const double h02 = -h00 - h01, h12 = -h01 - h11, h22 = h00 + 2.0 * h01 + h11;
  const double h23 = -h03 - h13;
  eq->hessian << h00, h01, h02, h03,
                 h01, h11, h12, h13,
                 h02, h12, h22, h23,
                 h03, h13, h23, h33;
  const double b0 = gbx * tp, b1 = gby * tp;
  eq->gradient << b0, b1, -b0 - b1, s.b2 * tr;
  s.SetTotals(kernel, static_cast<int>(scan.size()), eq);
}

}  // namespace

void LinearizeHex(const HexGrid& grid, const std::vector<Eigen::Vector3d>& scan,
                  const Eigen::Vector4d& xi, HexNormalEquations* eq, bool subcell_offsets,
                  double robust_loss_scale) {
  const RobustKernel kernel(robust_loss_scale);
  WithCompiledFlag(subcell_offsets, [&](auto subcell) {
    LinearizeHexWith<decltype(subcell)::value>(grid, scan, xi, kernel, eq);
  });
}

bool SolveLagrangeStep(const Eigen::Matrix4d& hessian, const Eigen::Vector4d& gradient,
                       Eigen::Vector4d* step) {
  // The null-space method: the steps with n·Δξ = 0 are Δξ = A y, A = CubePoseJacobian(), so the
  // first block row projected on the plane, AᵀHA y = Aᵀb, is the whole system (Aᵀn = 0 removes
  // λ), and it is nonsingular exactly when the 5×5 one is. A 3×3 LDLT instead of a 5×5
  // full-pivot LU: a few hundred operations less per iteration.
  const Eigen::Matrix<double, 4, 3> a = CubePoseJacobian();
  Eigen::Vector3d y;
  if (!SolvePositiveDefinite(a.transpose() * hessian * a, a.transpose() * gradient, &y)) {
    return false;
  }
  *step = a * y;
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

template class ScanMatcher<HexLattice>;

}  // namespace hex_slam
