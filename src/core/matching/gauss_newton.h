// The Gauss–Newton scan matcher of both lattices, private to the core: the sums of the normal
// equations, the iteration on one level (MinimizeLevel), and ScanMatcher<Lattice>'s coarse-to-fine
// loop. What differs between the lattices — the state, its linearisation and solve — is
// ScanMatcherTraits<Lattice> (hex_scan_matcher.h, square_scan_matcher.h); each lattice's .cpp
// instantiates the matcher.
#ifndef HEX_SLAM_SRC_CORE_GAUSS_NEWTON_H_
#define HEX_SLAM_SRC_CORE_GAUSS_NEWTON_H_

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "hex_slam/matching/scan_matcher.h"

namespace hex_slam {

// Σ w JᵀJ (its six distinct entries), Σ w J r, Σ ρ(r) and Σ M over a level's endpoints, for a
// Jacobian row J = (j0, j1, j2) of each and its residual r = 1 - M; w and ρ are the kernel's.
// Each lattice's linearisation feeds it the row in the coordinates its loop is cheapest in.
struct NormalSums {
  double h00 = 0.0, h01 = 0.0, h02 = 0.0, h11 = 0.0, h12 = 0.0, h22 = 0.0;
  double b0 = 0.0, b1 = 0.0, b2 = 0.0;
  double sum_value = 0.0;

  void Add(const RobustKernel& kernel, double value, double j0, double j1, double j2) {
    const double r = 1.0 - value;
    const double factor = kernel.Factor(r);
    const double w = 1.0 / factor;
    const double w0 = w * j0, w1 = w * j1, w2 = w * j2;
    h00 += w0 * j0, h01 += w0 * j1, h02 += w0 * j2;
    h11 += w1 * j1, h12 += w1 * j2;
    h22 += w2 * j2;
    b0 += w0 * r, b1 += w1 * r, b2 += w2 * r;
    // With the kernel on, the costs are kept as a product of factors and folded into a sum of
    // logarithms only when it grows large: a log1p per endpoint was a tenth of the scan path.
    if (kernel.enabled()) {
      if (factors_ > kFoldFactorsAbove) {
        folded_cost_ += kernel.CostOfProduct(factors_);
        factors_ = 1.0;
      }
      factors_ *= factor;
    } else {
      folded_cost_ += r * r;
    }
    sum_value += value;
  }
  // Σ ρ(r) over the endpoints added.
  double Cost(const RobustKernel& kernel) const {
    return kernel.enabled() ? folded_cost_ + kernel.CostOfProduct(factors_) : folded_cost_;
  }
  Eigen::Matrix3d Hessian() const {
    Eigen::Matrix3d h;
    h << h00, h01, h02,
         h01, h11, h12,
         h02, h12, h22;
    return h;
  }
  Eigen::Vector3d Gradient() const { return {b0, b1, b2}; }
  // What the equations of either lattice carry besides H and b.
  template <class Equations>
  void SetTotals(const RobustKernel& kernel, int count, Equations* eq) const {
    eq->cost = Cost(kernel);
    eq->sum_value = sum_value;
    eq->count = count;
  }

 private:
  // A factor is about 1 + 1/c² at most (residuals lie near [0, 1], c >= kMinRobustLossScale),
  // so a product folded above 1e100 stays far below the largest double.
  static constexpr double kFoldFactorsAbove = 1e100;
  double folded_cost_ = 0.0;
  double factors_ = 1.0;  // the product of the factors not yet folded (kernel on)
};

// Calls `loop(std::true_type())` or `loop(std::false_type())` as `flag` is: a per-endpoint loop
// compiled once for each value, so that the choice costs nothing per point.
template <class Loop>
void WithCompiledFlag(bool flag, Loop loop) {
  if (flag) {
    loop(std::true_type());
  } else {
    loop(std::false_type());
  }
}

// H x = b for a 3×3 H that must be positive definite; false (x untouched) when it is not.
inline bool SolvePositiveDefinite(const Eigen::Matrix3d& hessian, const Eigen::Vector3d& gradient,
                                  Eigen::Vector3d* solution) {
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(hessian);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().minCoeff() > 0.0)) {
    return false;
  }
  const Eigen::Vector3d x = ldlt.solve(gradient);
  if (!x.allFinite()) return false;
  *solution = x;
  return true;
}

// The iteration on one level: linearise, solve, clamp, keep the step only if the cost did not
// rise (a half step is tried once), stop on a small step or the cap. A small step is checked
// like any other only with `verify_converged_step` (ScanMatcherOptions::verify_converged_step);
// otherwise it is taken and the level ends. A Problem supplies
//   State, Equations, double Linearize(const State&, Equations*) const,
//   bool Solve(const Equations&, State* step) const, State Apply(const State&, const State& step)
//   const (with clamps), bool Small(const State& step) const.
template <class Problem>
typename Problem::State MinimizeLevel(const Problem& problem, typename Problem::State state,
                                      int max_iterations, bool verify_converged_step,
                                      typename Problem::Equations* eq, LevelReport* report) {
  using State = typename Problem::State;
  constexpr double kBacktrackFactor = 0.5;
  const auto linearize = [&problem, report](const State& at, typename Problem::Equations* out) {
    ++report->linearizations;
    return problem.Linearize(at, out);
  };
  double cost = linearize(state, eq);
  typename Problem::Equations trial_eq;
  for (int it = 0; it < max_iterations; ++it) {
    State step;
    if (!problem.Solve(*eq, &step)) break;
    ++report->iterations;
    State trial = problem.Apply(state, step);
    if (!verify_converged_step && problem.Small(step)) {
      // `eq` and `cost` stay those of the pose before this last, negligible step.
      state = trial;
      report->converged = true;
      break;
    }
    double trial_cost = linearize(trial, &trial_eq);
    if (trial_cost > cost) {
      step *= kBacktrackFactor;
      trial = problem.Apply(state, step);
      trial_cost = linearize(trial, &trial_eq);
      if (trial_cost > cost) {
        ++report->rejected_steps;
        break;
      }
    }
    state = trial;
    cost = trial_cost;
    *eq = trial_eq;
    if (problem.Small(step)) {
      report->converged = true;
      break;
    }
  }
  report->cost = cost;
  return state;
}

// One pyramid level as MinimizeLevel's Problem, on either lattice. Both states end with the
// heading; the coordinates before it are the translation, whose Cartesian length the traits give.
template <class Lattice>
class LevelProblem {
 public:
  using Traits = ScanMatcherTraits<Lattice>;
  using State = typename Traits::State;
  using Equations = typename Traits::Equations;
  using Points = std::vector<typename Traits::Point>;

  LevelProblem(const GridMap<Lattice>& grid, const Points& scan, const ScanMatcherOptions& options,
               bool coarsest, bool subcell_offsets, double angle_tolerance)
      : grid_(grid),
        scan_(scan),
        max_angle_step_(options.max_angle_step),
        max_translation_(options.max_translation_step_cells * grid.lattice().spacing()),
        translation_tolerance_(options.translation_tolerance_cells * grid.lattice().spacing()),
        angle_tolerance_(angle_tolerance),
        robust_loss_scale_(options.LevelRobustLossScale(coarsest)),
        subcell_offsets_(subcell_offsets) {}

  double Linearize(const State& state, Equations* eq) const {
    Traits::Linearize(grid_, scan_, state, eq, subcell_offsets_, robust_loss_scale_);
    AddPull(state, 1.0, eq);
    return eq->cost;
  }
  // Pulls the translation towards `target`'s: the cost gains per_point_weight·N·|t - t_target|²
  // (metres). A Cartesian unit step's squared length in the state's translation coordinates (1 on
  // the square lattice, 1.5 in cube coordinates) converts it, so the pull is the same on both.
  void PullTowards(const Pose2& target, double per_point_weight) {
    target_ = Traits::FromPose(target);
    const State unit = Traits::FromPose(Pose2(1.0, 0.0, 0.0));
    pull_weight_ = per_point_weight * static_cast<double>(scan_.size()) /
                   unit.template head<kHeading>().squaredNorm();
  }
  // `eq` (linearised at `state`) without the pull: what the map alone says. (A level that ends
  // on a step too small to verify has `eq` from just before it; the cost is then off by that
  // step's share of the pull, never below zero.)
  void RemovePull(const State& state, Equations* eq) const {
    AddPull(state, -1.0, eq);
    eq->cost = std::max(eq->cost, 0.0);
  }
  bool Solve(const Equations& eq, State* step) const { return Traits::Solve(eq, step); }
  State Apply(const State& state, State step) const {
    const double t = Traits::TranslationLength(step);
    if (t > max_translation_) step.template head<kHeading>() *= max_translation_ / t;
    step[kHeading] = std::max(-max_angle_step_, std::min(max_angle_step_, step[kHeading]));
    return Traits::Add(state, step);
  }
  bool Small(const State& step) const {
    return Traits::TranslationLength(step) < translation_tolerance_ &&
           std::abs(step[kHeading]) < angle_tolerance_;
  }

 private:
  static constexpr int kHeading = State::RowsAtCompileTime - 1;

  // cost += w|t_target - t|², as a residual √w (t_target - t) whose row is √w: the Hessian gains
  // w and the gradient w (t_target - t), the sign convention of the map's residuals. `sign` -1
  // takes it back out.
  void AddPull(const State& state, double sign, Equations* eq) const {
    if (pull_weight_ == 0.0) return;
    const double w = sign * pull_weight_;
    const auto d = (target_ - state).template head<kHeading>().eval();
    for (int i = 0; i < kHeading; ++i) {
      eq->hessian(i, i) += w;
      eq->gradient[i] += w * d[i];
    }
    eq->cost += w * d.squaredNorm();
  }

  State target_ = State::Zero();
  double pull_weight_ = 0.0;

  const GridMap<Lattice>& grid_;
  const Points& scan_;
  double max_angle_step_;
  double max_translation_;
  double translation_tolerance_;
  double angle_tolerance_;
  double robust_loss_scale_;
  bool subcell_offsets_;
};

// `points` as the lattice's linearisation reads them, keeping only endpoints `min_spacing` apart
// (ForEachKeptEndpoint). Points the lattice reads as they are, all kept, are not copied.
template <class Traits>
const std::vector<typename Traits::Point>& LevelEndpoints(
    const std::vector<Eigen::Vector2d>& points, double min_spacing,
    std::vector<typename Traits::Point>* scratch) {
  if constexpr (std::is_same<typename Traits::Point, Eigen::Vector2d>::value) {
    if (min_spacing <= 0.0) return points;
  }
  scratch->clear();
  ForEachKeptEndpoint(points, min_spacing,
                      [scratch](const Eigen::Vector2d& p) { scratch->push_back(Traits::ToPoint(p)); });
  return *scratch;
}

template <class Lattice>
MatchResult ScanMatcher<Lattice>::Match(const MapPyramid<Lattice>& maps,
                                        const std::vector<Eigen::Vector2d>& points,
                                        const Pose2& guess, GuessSource source) const {
  using Traits = ScanMatcherTraits<Lattice>;
  MatchResult result;
  result.levels.resize(maps.size());
  typename Traits::State state = Traits::FromPose(guess);
  typename Traits::Equations eq;
  const double reach = options_.coarsest_min_move_cells > 0.0 ? Reach(points) : 0.0;
  const double mean_range = MeanRange(points);
  for (int level = maps.size() - 1; level >= 0; --level) {
    const GridMap<Lattice>& grid = maps.level(level);
    const double spacing = grid.lattice().spacing();
    const bool finest = level == 0;
    const std::vector<typename Traits::Point>& scan = LevelEndpoints<Traits>(
        points, finest ? 0.0 : options_.coarse_point_spacing_cells * spacing, &scan_);
    // Sub-cell offsets on every level but the coarsest: there they would warp the smooth field
    // that level exists for and shrink the basin of convergence.
    const bool coarsest = level == maps.size() - 1 && maps.size() > 1;
    const double translation_tolerance = options_.translation_tolerance_cells * spacing;
    LevelProblem<Lattice> problem(
        grid, scan, options_, coarsest, options_.subcell_offsets && !coarsest,
        options_.LevelAngleTolerance(translation_tolerance, mean_range));
    if (source == GuessSource::kOdometry && options_.odometry_translation_weight > 0.0) {
      problem.PullTowards(guess, options_.odometry_translation_weight);
    }
    LevelReport& report = result.levels[level];
    report.points = static_cast<int>(scan.size());
    const typename Traits::State before = state;
    state = MinimizeLevel(problem, state,
                          finest ? options_.max_iterations_fine : options_.max_iterations_coarse,
                          options_.verify_converged_step, &eq, &report);
    problem.RemovePull(state, &eq);
    const double moved = EndpointMoveBound(Traits::ToPose(before), Traits::ToPose(state), reach);
    if (coarsest && moved < options_.coarsest_min_move_cells * spacing) {
      state = before;
      report.move_dropped = true;
    }
  }
  result.pose = Traits::ToPose(state);
  result.hessian = Traits::PoseHessian(eq.hessian);
  result.cost = eq.cost;
  result.num_points = eq.count;
  result.mean_occupancy = eq.count > 0 ? eq.sum_value / eq.count : 0.0;
  result.covariance = CovarianceFromHessian(result.hessian, eq.cost, eq.count);
  return result;
}

}  // namespace hex_slam

#endif  // HEX_SLAM_SRC_CORE_GAUSS_NEWTON_H_
