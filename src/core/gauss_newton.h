// The iteration shared by both lattices' matchers: linearise, solve, clamp, keep the step only if
// the cost did not rise (a half step is tried once), stop on a small step or the cap. A small
// step is checked like any other only with `verify_converged_step`
// (ScanMatcherOptions::verify_converged_step); otherwise it is taken and the level ends.
// Private to the core: each matcher supplies a Problem with
//   State, Equations, double Linearize(const State&, Equations*) const,
//   bool Solve(const Equations&, State* step) const, State Apply(const State&, const State& step)
//   const (with clamps), bool Small(const State& step) const.
#ifndef HEX_SLAM_SRC_CORE_GAUSS_NEWTON_H_
#define HEX_SLAM_SRC_CORE_GAUSS_NEWTON_H_

#include "hex_slam/scan_matcher.h"

namespace hex_slam {

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

}  // namespace hex_slam

#endif  // HEX_SLAM_SRC_CORE_GAUSS_NEWTON_H_
