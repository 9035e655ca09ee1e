#include "hex_slam/mapping/loop_closure/constraint_builder.h"

#include <chrono>
#include <algorithm>
#include <cmath>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/gauss_newton_matcher.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {
std::vector<std::string> ConstraintBuilderOptions::Validate() const {
  std::vector<std::string> errors = matcher.Validate();
  auto require = [&errors](bool ok, const std::string& message) {
    if (!ok) errors.push_back(message);
  };
  auto fraction = [](double v) { return v >= 0.0 && v <= 1.0; };
  require(max_constraint_distance >= 0.0 && std::isfinite(max_constraint_distance),
          "loop_closure_max_constraint_distance must be finite and >= 0");
  require(min_linear_search_window >= 0.0 && std::isfinite(min_linear_search_window),
          "loop_closure_min_linear_search_window must be finite and >= 0");
  require(search_window_growth >= 0.0 && std::isfinite(search_window_growth),
          "loop_closure_search_window_growth must be finite and >= 0");
  require(min_angular_search_window >= 0.0 && min_angular_search_window <= M_PI,
          "loop_closure_min_angular_search_window must lie in [0, pi]");
  require(angular_search_window_growth >= 0.0 && std::isfinite(angular_search_window_growth),
          "loop_closure_angular_search_window_growth must be finite and >= 0");
  require(fraction(sampling_ratio), "loop_closure_sampling_ratio must lie in [0, 1]");
  require(fraction(min_score), "loop_closure_min_score must lie in [0, 1]");
  require(fraction(global_localization_min_score),
          "loop_closure_global_min_score must lie in [0, 1]");
  require(global_constraint_search_after_n_seconds >= 0.0,
          "loop_closure_global_search_after must be >= 0");
  require(fraction(global_sampling_ratio), "loop_closure_global_sampling_ratio must lie in [0, 1]");
  require(global_confirm_min_distance >= 0.0 && std::isfinite(global_confirm_min_distance),
          "loop_closure_global_confirm_min_distance must be finite and >= 0");
  require(global_confirm_max_distance >= 0.0 && std::isfinite(global_confirm_max_distance),
          "loop_closure_global_confirm_max_distance must be finite and >= 0");
  require(global_confirm_max_distance == 0.0 ||
              global_confirm_max_distance >= global_confirm_min_distance,
          "loop_closure_global_confirm_max_distance must be 0 or >= "
          "loop_closure_global_confirm_min_distance");
  require(point_spacing >= 0.0 && std::isfinite(point_spacing),
          "loop_closure_point_spacing must be finite and >= 0");
  require(search_level >= 0, "loop_closure_search_level must be >= 0");
  require(global_search_level >= 0, "loop_closure_global_search_level must be >= 0");
  require(submap_cache_mb >= 0.0 && std::isfinite(submap_cache_mb),
          "loop_closure_submap_cache_mb must be finite and >= 0");
  return errors;
}

template <class Lattice>
ConstraintBuilder<Lattice>::ConstraintBuilder(const ConstraintBuilderOptions& options,
                                              const ScanMatcherOptions& refinement)
    : options_(options), refinement_(refinement) {}

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

template <class Lattice>
std::optional<Constraint> ConstraintBuilder<Lattice>::Search(
    const Submap<Lattice>& submap, const matching::FastCorrelativeScanMatcher<Lattice>& matcher,
    const TrajectoryNode& node, const Pose2& expected, double distance, bool global) {
  const std::optional<matching::CorrelativeMatch> match =
      Find(submap.local_pose(), matcher, node, expected, distance, global);
  if (!match) return std::nullopt;
  return Refine(submap, node, *match);
}

template <class Lattice>
std::optional<matching::CorrelativeMatch> ConstraintBuilder<Lattice>::Find(
    const Pose2& submap_local_pose, const matching::FastCorrelativeScanMatcher<Lattice>& matcher,
    const TrajectoryNode& node, const Pose2& expected, double distance, bool global) {
  const auto start = std::chrono::steady_clock::now();
  ++(global ? stats_.global_searches : stats_.local_searches);
  std::vector<Eigen::Vector2d> points;
  DecimateScan(node.points, options_.point_spacing, &points);
  // The grid is in the local frame the submap was built in; the submap's frame is local_pose.
  const Pose2 on_grid = submap_local_pose * expected;
  std::optional<matching::CorrelativeMatch> match =
      global ? matcher.MatchFullSubmap(points, options_.global_localization_min_score)
             : matcher.Match(on_grid, points, options_.min_score, LinearWindow(distance),
                             AngularWindow(distance));
  if (match) stats_.candidates += match->candidates;
  if (match && match->runner_up_score > 0.0) ++stats_.ambiguous;
  stats_.search_seconds += SecondsSince(start);
  if (!match || match->runner_up_score > 0.0) return std::nullopt;
  ++(global ? stats_.global_found : stats_.local_found);
  return match;
}

template <class Lattice>
Constraint ConstraintBuilder<Lattice>::Refine(const Submap<Lattice>& submap,
                                              const TrajectoryNode& node,
                                              const matching::CorrelativeMatch& match) {
  const auto start = std::chrono::steady_clock::now();
  // Gauss–Newton from the branch-and-bound pose, which is within a cell and an angular step of
  // the optimum; a refinement that wanders off by more than a coarsest cell has lost its way.
  const MapPyramid<Lattice>& maps = submap.maps();
  const MatchResult refined =
      matching::GaussNewtonMatcher<Lattice>(refinement_).Match(maps, node.points, match.pose);
  const double coarsest_cell = maps.level(maps.size() - 1).lattice().spacing();
  const bool kept = refined.num_points > 0 &&
                    (refined.pose.translation() - match.pose.translation()).norm() <= coarsest_cell;
  const Pose2 pose = kept ? refined.pose : match.pose;
  stats_.search_seconds += SecondsSince(start);
  return Constraint{submap.id(), node.id, RelativePose(submap.local_pose(), pose),
                    ConstraintTag::kLoop, match.score};
}

template <class Lattice>
std::optional<Pose2> ConstraintBuilder<Lattice>::BestPlace(
    const Pose2& submap_local_pose, const matching::FastCorrelativeScanMatcher<Lattice>& matcher,
    const TrajectoryNode& node, double min_score) {
  const auto start = std::chrono::steady_clock::now();
  ++stats_.global_searches;
  std::vector<Eigen::Vector2d> points;
  DecimateScan(node.points, options_.point_spacing, &points);
  const std::optional<matching::CorrelativeMatch> match =
      matcher.MatchFullSubmap(points, min_score);
  if (match) stats_.candidates += match->candidates;
  stats_.search_seconds += SecondsSince(start);
  if (!match) return std::nullopt;
  return RelativePose(submap_local_pose, match->pose);
}

template <class Lattice>
double ConstraintBuilder<Lattice>::LinearWindow(double distance) const {
  return std::min(options_.matcher.linear_search_window,
                  options_.min_linear_search_window + options_.search_window_growth * distance);
}

template <class Lattice>
double ConstraintBuilder<Lattice>::AngularWindow(double distance) const {
  return std::min(options_.matcher.angular_search_window,
                  options_.min_angular_search_window +
                      options_.angular_search_window_growth * distance);
}

template <class Lattice>
double ConstraintBuilder<Lattice>::WindowsFullFrom() const {
  const auto full_from = [](double widest, double narrowest, double growth) {
    return growth > 0.0 ? std::max(0.0, (widest - narrowest) / growth) : 0.0;
  };
  return std::max(full_from(options_.matcher.linear_search_window,
                            options_.min_linear_search_window, options_.search_window_growth),
                  full_from(options_.matcher.angular_search_window,
                            options_.min_angular_search_window,
                            options_.angular_search_window_growth));
}

template class ConstraintBuilder<HexLattice>;
template class ConstraintBuilder<SquareLattice>;

}  // namespace mapping
}  // namespace hex_slam
