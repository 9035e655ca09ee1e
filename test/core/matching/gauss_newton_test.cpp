// MinimizeLevel (src/core/matching/gauss_newton.h, private to the core) on a problem small enough to count
// its passes exactly: f(x) = Σ (x_i - target_i)², whose Gauss–Newton step is exact; the shared
// normal-equation sums and solve against Eigen's dense algebra.
#include "../../../src/core/matching/gauss_newton.h"

#include <cmath>
#include <random>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace hex_slam {
namespace {

struct QuadraticProblem {
  using State = Eigen::Vector2d;
  struct Equations {
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
    double cost = 0.0;
  };
  Eigen::Vector2d target;
  double max_step = 1e9;
  double tolerance = 1e-6;

  double Linearize(const State& x, Equations* eq) const {
    eq->gradient = target - x;
    eq->cost = (target - x).squaredNorm();
    return eq->cost;
  }
  bool Solve(const Equations& eq, State* step) const {
    *step = eq.gradient;  // H = I
    return true;
  }
  State Apply(const State& x, State step) const {
    if (step.norm() > max_step) step *= max_step / step.norm();
    return x + step;
  }
  bool Small(const State& step) const { return step.norm() < tolerance; }
};

TEST(GaussNewtonTest, AVerifiedConvergedStepCostsOneMorePass) {
  const QuadraticProblem problem{Eigen::Vector2d(3.0, -1.0)};
  for (bool verify : {true, false}) {
    QuadraticProblem::Equations eq;
    LevelReport report;
    const Eigen::Vector2d x =
        MinimizeLevel(problem, Eigen::Vector2d::Zero(), 10, verify, &eq, &report);
    EXPECT_NEAR((x - problem.target).norm(), 0.0, 1e-12);
    EXPECT_TRUE(report.converged);
    // The exact step, then a zero one that meets the tolerance.
    EXPECT_EQ(report.iterations, 2);
    // First pass, the pass after the exact step, and (verified) the pass after the zero step.
    EXPECT_EQ(report.linearizations, verify ? 3 : 2) << verify;
  }
}

TEST(GaussNewtonTest, UnverifiedOnlyTheStepWithinTheToleranceGoesUnchecked) {
  // Clamped steps of 1 take four iterations to cover 3.2; each is checked (one pass after it);
  // the last, 0.2 long, is above the tolerance too, then the zero step ends the level unchecked.
  QuadraticProblem problem{Eigen::Vector2d(3.2, 0.0)};
  problem.max_step = 1.0;
  QuadraticProblem::Equations eq;
  LevelReport report;
  const Eigen::Vector2d x =
      MinimizeLevel(problem, Eigen::Vector2d::Zero(), 10, false, &eq, &report);
  EXPECT_NEAR(x.x(), 3.2, 1e-12);
  EXPECT_EQ(report.iterations, 5);
  EXPECT_EQ(report.linearizations, 5);
  // The equations are those of the last checked pose.
  EXPECT_NEAR(eq.cost, 0.0, 1e-20);
}

TEST(GaussNewtonTest, NormalSumsAreTheWeightedDenseSums) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const RobustKernel kernel(0.3);
  NormalSums sums;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double cost = 0.0;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d j(u(rng), u(rng), u(rng));
    const double value = 0.5 + 0.5 * u(rng);
    const double r = 1.0 - value;
    sums.Add(kernel, value, j.x(), j.y(), j.z());
    h += kernel.Weight(r) * j * j.transpose();
    b += kernel.Weight(r) * r * j;
    cost += kernel.Cost(r);
  }
  EXPECT_LT((sums.Hessian() - h).norm(), 1e-12);
  EXPECT_LT((sums.Gradient() - b).norm(), 1e-12);
  EXPECT_NEAR(sums.Cost(kernel), cost, 1e-12);
}

// The robust cost is kept as a product of factors and folded into logarithms when the product
// grows large: over many endpoints, at the smallest allowed scale (the largest factors) and at
// the usual one, it must equal the sum of each endpoint's ρ(r), and plain least squares Σ r².
TEST(GaussNewtonTest, NormalSumsCostOverManyEndpointsIsTheSumOfEachOnesCost) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double scale : {0.0, kMinRobustLossScale, 0.01, 0.3, 5.0}) {
    const RobustKernel kernel(scale);
    NormalSums sums;
    double cost = 0.0;
    for (int i = 0; i < 20000; ++i) {
      // Some endpoints exactly on a wall (r = 0), the rest anywhere up to free space (r = 1).
      const double value = i % 7 == 0 ? 1.0 : u(rng);
      sums.Add(kernel, value, 0.0, 0.0, 0.0);
      cost += kernel.Cost(1.0 - value);
    }
    EXPECT_NEAR(sums.Cost(kernel), cost, 1e-12 * cost) << "scale " << scale;
    EXPECT_TRUE(std::isfinite(sums.Cost(kernel)));
  }
}

TEST(GaussNewtonTest, SolvePositiveDefiniteSolvesOnlyAPositiveDefiniteSystem) {
  Eigen::Matrix3d h;
  h << 4.0, 1.0, 0.5,
       1.0, 3.0, 0.2,
       0.5, 0.2, 2.0;
  const Eigen::Vector3d b(1.0, -2.0, 0.5);
  Eigen::Vector3d x = Eigen::Vector3d::Constant(7.0);
  ASSERT_TRUE(SolvePositiveDefinite(h, b, &x));
  EXPECT_LT((h * x - b).norm(), 1e-12);
  // Singular (a direction the scan does not constrain) and indefinite: refused, x untouched.
  const Eigen::Matrix3d singular = Eigen::Vector3d(1.0, 2.0, 0.0).asDiagonal();
  const Eigen::Matrix3d indefinite = Eigen::Vector3d(1.0, -2.0, 3.0).asDiagonal();
  x = Eigen::Vector3d::Constant(7.0);
  EXPECT_FALSE(SolvePositiveDefinite(singular, b, &x));
  EXPECT_FALSE(SolvePositiveDefinite(indefinite, b, &x));
  EXPECT_EQ(x, Eigen::Vector3d::Constant(7.0));
}

}  // namespace
}  // namespace hex_slam
