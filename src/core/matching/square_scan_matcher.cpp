#include "hex_slam/matching/square_scan_matcher.h"

#include <cmath>
#include <vector>

#include "matching/gauss_newton.h"
#include "hex_slam/map/bilinear_interpolation.h"

namespace hex_slam {
namespace {

// The loop of LinearizeSquare, compiled once per interpolation.
template <bool kSubcell>
void LinearizeSquareWith(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                         const Eigen::Vector3d& pose, const RobustKernel& kernel,
                         SquareNormalEquations* eq) {
  const double c = std::cos(pose[2]);
  const double s = std::sin(pose[2]);
  NormalSums sums;
  for (const Eigen::Vector2d& p : scan) {
    const double rx = c * p.x() - s * p.y();
    const double ry = s * p.x() + c * p.y();
    const Eigen::Vector2d world(rx + pose.x(), ry + pose.y());
    const SquareSample sample =
        kSubcell ? InterpolateBilinearSubcell(grid, world) : InterpolateBilinear(grid, world);
    const double gx = sample.gradient.x(), gy = sample.gradient.y();
    sums.Add(kernel, sample.value, gx, gy, -gx * ry + gy * rx);
  }
  eq->hessian = sums.Hessian();
  eq->gradient = sums.Gradient();
  sums.SetTotals(kernel, static_cast<int>(scan.size()), eq);
}

}  // namespace

void LinearizeSquare(const SquareGrid& grid, const std::vector<Eigen::Vector2d>& scan,
                     const Eigen::Vector3d& pose, SquareNormalEquations* eq, bool subcell_offsets,
                     double robust_loss_scale) {
  const RobustKernel kernel(robust_loss_scale);
  WithCompiledFlag(subcell_offsets, [&](auto subcell) {
    LinearizeSquareWith<decltype(subcell)::value>(grid, scan, pose, kernel, eq);
  });
}

bool ScanMatcherTraits<SquareLattice>::Solve(const Equations& eq, State* step) {
  return SolvePositiveDefinite(eq.hessian, eq.gradient, step);
}

template class ScanMatcher<SquareLattice>;

}  // namespace hex_slam
