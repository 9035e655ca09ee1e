#include "hex_slam/mapping/slam_options.h"

#include <cmath>
#include <string>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {

int EffectiveLevels(const SlamOptions& options) {
  int wanted = options.map_multi_res_levels;
  // The coarsest of `wanted` levels has spacing map_resolution * 2^(wanted - 1).
  while (wanted < kMaxMapLevels &&
         options.map_resolution * std::ldexp(1.0, wanted - 1) < options.map_min_coarse_resolution) {
    ++wanted;
  }
  int levels = 1;
  double spacing = 2.0 * options.map_resolution;
  const bool capped = options.map_max_coarse_resolution > 0.0;
  while (levels < wanted && (!capped || spacing <= options.map_max_coarse_resolution)) {
    ++levels;
    spacing *= 2.0;
  }
  return levels;
}

GridGrowthPolicy MapGrowthPolicy(const SlamOptions& o) {
  GridGrowthPolicy growth;
  growth.auto_grow = o.map_auto_grow;
  growth.max_cells = o.map_max_cells;
  return growth;
}

OccupancyModel MapOccupancyModel(const SlamOptions& o) {
  return OccupancyModel::FromFactors(o.update_factor_free, o.update_factor_occupied,
                                     o.log_odds_limit);
}

Eigen::AlignedBox2d InitialMapExtent(const SlamOptions& o) {
  const double side = o.map_size * o.map_resolution;
  const Eigen::Vector2d lo(-o.map_start_x * side, -o.map_start_y * side);
  return Eigen::AlignedBox2d(lo, lo + Eigen::Vector2d(side, side));
}

namespace {

// The cells the finest level allocates for InitialMapExtent: more than map_size^2 on hexagons
// (their columns are closer than the spacing) and with the storage's margin on either lattice.
template <class Lattice>
double InitialStorageCells(const SlamOptions& o) {
  GridIndex lo, hi;
  Lattice(o.map_resolution).IndexBounds(InitialMapExtent(o), &lo, &hi);
  return (static_cast<double>(hi.col) - lo.col + 1.0) * (static_cast<double>(hi.row) - lo.row + 1.0);
}

}  // namespace

std::vector<std::string> SlamOptions::Validate() const {
  std::vector<std::string> errors = matcher.Validate();
  for (const std::string& e : recovery.Validate()) errors.push_back(e);
  for (const std::string& e : tracking.Validate()) errors.push_back(e);
  for (const std::string& e : loop_closure.Validate()) errors.push_back(e);
  for (const std::string& e : global_localization.Validate()) errors.push_back(e);
  auto require = [&errors](bool ok, const std::string& message) {
    if (!ok) errors.push_back(message);
  };
  require(lattice == "hex" || lattice == "square",
          "lattice must be 'hex' or 'square', got '" + lattice + "'");
  require(map_resolution > 0.0 && std::isfinite(map_resolution),
          "map_resolution must be > 0 and finite");
  require(map_size >= 16, "map_size must be >= 16 cells");
  require(map_start_x >= 0.0 && map_start_x <= 1.0, "map_start_x must lie in [0, 1]");
  require(map_start_y >= 0.0 && map_start_y <= 1.0, "map_start_y must lie in [0, 1]");
  require(map_multi_res_levels >= 1 && map_multi_res_levels <= kMaxMapLevels,
          "map_multi_res_levels must lie in [1, " + std::to_string(kMaxMapLevels) + "]");
  require(map_max_coarse_resolution >= 0.0, "map_max_coarse_resolution must be >= 0 (0: none)");
  require(map_min_coarse_resolution >= 0.0 &&
              (map_max_coarse_resolution == 0.0 ||
               map_min_coarse_resolution <= map_max_coarse_resolution),
          "map_min_coarse_resolution must lie in [0, map_max_coarse_resolution]");
  require(update_factor_free > 0.0 && update_factor_free < 0.5,
          "update_factor_free must lie in (0, 0.5)");
  require(update_factor_occupied > 0.5 && update_factor_occupied < 1.0,
          "update_factor_occupied must lie in (0.5, 1)");
  require(map_update_distance_thresh >= 0.0, "map_update_distance_thresh must be >= 0");
  require(map_update_angle_thresh >= 0.0, "map_update_angle_thresh must be >= 0");
  require(map_update_score_margin >= 0.0 && map_update_score_margin <= 1.0,
          "map_update_score_margin must lie in [0, 1]");
  require(map_update_min_distance >= 0.0, "map_update_min_distance must be >= 0");
  // Only when the storage is well defined (the checks above name what is not).
  if (map_resolution > 0.0 && std::isfinite(map_resolution) && map_size >= 16 &&
      map_start_x >= 0.0 && map_start_x <= 1.0 && map_start_y >= 0.0 && map_start_y <= 1.0) {
    const double initial = lattice == "square" ? InitialStorageCells<SquareLattice>(*this)
                                               : InitialStorageCells<HexLattice>(*this);
    require(static_cast<double>(map_max_cells) >= initial,
            "map_max_cells must hold the initial map_size x map_size storage (" +
                std::to_string(static_cast<std::int64_t>(initial)) + " cells here)");
  }
  require(map_max_cells <= kMaxMapCells,
          "map_max_cells must be <= " + std::to_string(kMaxMapCells) + " (the hard limit)");
  require(odometry_jump_distance_thresh > 0.0, "odometry_jump_distance_thresh must be > 0");
  require(odometry_jump_angle_thresh > 0.0 && odometry_jump_angle_thresh <= M_PI,
          "odometry_jump_angle_thresh must lie in (0, pi]");
  require(constant_velocity_horizon >= 0.0 && std::isfinite(constant_velocity_horizon),
          "constant_velocity_horizon must be >= 0 and finite");
  require(log_odds_limit > 0.0, "log_odds_limit must be > 0");
  require(laser_min_dist >= 0.0, "laser_min_dist must be >= 0");
  require(laser_max_dist > laser_min_dist, "laser_max_dist must exceed laser_min_dist");
  require(laser_z_max_value > laser_z_min_value,
          "laser_z_max_value must exceed laser_z_min_value");
  require(laser_match_max_incidence > 0.0 && laser_match_max_incidence <= 0.5 * M_PI,
          "laser_match_max_incidence must lie in (0, pi/2] (pi/2: off)");
  require(min_valid_beams >= 3, "min_valid_beams must be >= 3");
  require(laser_range_max_margin >= 0.0 && std::isfinite(laser_range_max_margin),
          "laser_range_max_margin must be finite and >= 0");
  require(recovery_score_ratio >= 0.0 && recovery_score_ratio < 1.0,
          "recovery_score_ratio must lie in [0, 1)");
  require(recovery_wide_linear_window >= 0.0 && std::isfinite(recovery_wide_linear_window),
          "recovery_wide_linear_window must be finite and >= 0");
  require(recovery_wide_angular_window >= 0.0 && recovery_wide_angular_window <= M_PI,
          "recovery_wide_angular_window must lie in [0, pi]");
  require(recovery_wide_collapse_ratio >= 0.0 && recovery_wide_collapse_ratio <= 1.0,
          "recovery_wide_collapse_ratio must lie in [0, 1]");
  require(prediction_acc_lim_x >= 0.0 && std::isfinite(prediction_acc_lim_x),
          "prediction_acc_lim_x must be finite and >= 0");
  require(prediction_acc_lim_theta >= 0.0 && std::isfinite(prediction_acc_lim_theta),
          "prediction_acc_lim_theta must be finite and >= 0");
  return errors;
}

namespace {

void AddGlobalLocalizationParameters(mapping::GlobalLocalizationOptions* g, ParameterTable* t) {
  t->Add("global_localization", &g->enabled,
         "on a loaded map with update_map false: search the whole map for the robot while lost, "
         "or while the scans do not confirm the pose it was given");
  t->Add("global_localization_min_score", &g->min_score,
         "the whole-map search's best pose counts above this score (mean cell probability)");
  t->Add("global_localization_search_level", &g->search_level,
         "pyramid level the whole-map search runs on (0: finest; the coarsest at most)");
  t->Add("global_localization_point_spacing", &g->point_spacing,
         "the searched scan keeps consecutive endpoints at least this far apart (m)");
  t->Add("global_localization_background", &g->background,
         "run the search on a background thread (false: within the scan that starts it)");
  t->Add("global_localization_branch_and_bound_depth", &g->matcher.branch_and_bound_depth,
         "precomputed grid depths; the coarsest bounds 2^(depth-1) cells per side");
  t->Add("global_localization_ambiguity_ratio", &g->matcher.ambiguity_ratio,
         "refuse the pose when another place scores this fraction of it (0: no check)");
  t->Add("global_localization_peak_radius", &g->matcher.peak_radius,
         "poses this close to the best (m) belong to its peak, not another place");
}

// Cartographer's names where the concept is the same (see docs/ros.md), prefixed by the part.
void AddLoopClosureParameters(mapping::LoopClosureOptions* l, ParameterTable* t) {
  t->Add("loop_closure", &l->enabled,
         "match against submaps and close loops in a pose graph (false: one map, no back end, "
         "as hector)");
  t->Add("submap_num_scans", &l->submaps.num_scans,
         "scans inserted into a submap before the next starts; finished at twice this");
  t->Add("submap_node_point_spacing_cells", &l->submaps.node_point_spacing_cells,
         "a node keeps consecutive endpoints at least this many finest cells apart");
  mapping::ConstraintBuilderOptions& c = l->constraints;
  t->Add("loop_closure_max_constraint_distance", &c.max_constraint_distance,
         "search a node on finished submaps whose origin is this close to it (m)");
  t->Add("loop_closure_min_linear_search_window", &c.min_linear_search_window,
         "local search half-width (m) for a submap the path was just tied to; it grows from there");
  t->Add("loop_closure_search_window_growth", &c.search_window_growth,
         "local search half-width added per metre of path since the last node tied to the submap");
  t->Add("loop_closure_min_angular_search_window", &c.min_angular_search_window,
         "local search half-width in heading (rad) for a submap the path was just tied to");
  t->Add("loop_closure_angular_search_window_growth", &c.angular_search_window_growth,
         "heading half-width added per metre of path since the last node tied to the submap (rad/m)");
  t->Add("loop_closure_sampling_ratio", &c.sampling_ratio,
         "fraction of the (node, submap) pairs within reach that are searched");
  t->Add("loop_closure_min_score", &c.min_score,
         "a local search's match becomes a constraint above this score (mean cell probability)");
  t->Add("loop_closure_global_min_score", &c.global_localization_min_score,
         "a global (full-submap) search's match becomes a constraint above this score");
  t->Add("loop_closure_global_search_after", &c.global_constraint_search_after_n_seconds,
         "after this long without a loop constraint (s), search sampled nodes on every submap");
  t->Add("loop_closure_global_sampling_ratio", &c.global_sampling_ratio,
         "fraction of the nodes searched on every submap when a global search is due");
  t->Add("loop_closure_global_confirm_min_distance", &c.global_confirm_min_distance,
         "a global match is taken once a node at least this far on (m) is found where it says");
  t->Add("loop_closure_global_confirm_max_distance", &c.global_confirm_max_distance,
         "a global match no node confirms within this path length (m) is dropped; 0: taken at once");
  t->Add("loop_closure_point_spacing", &c.point_spacing,
         "the searched scan keeps consecutive endpoints at least this far apart (m)");
  t->Add("loop_closure_search_level", &c.search_level,
         "pyramid level the branch-and-bound search runs on (0: finest)");
  t->Add("loop_closure_global_search_level", &c.global_search_level,
         "pyramid level the global (full-submap) searches run on");
  t->Add("loop_closure_submap_cache_mb", &c.submap_cache_mb,
         "memory for finished submaps and their search grids (MB); beyond it they are redrawn");
  t->Add("loop_closure_linear_search_window", &c.matcher.linear_search_window,
         "largest local search half-width in x and y around the expected pose (m)");
  t->Add("loop_closure_angular_search_window", &c.matcher.angular_search_window,
         "largest local search half-width in heading (rad)");
  t->Add("loop_closure_branch_and_bound_depth", &c.matcher.branch_and_bound_depth,
         "precomputed grid depths; the coarsest bounds 2^(depth-1) cells per side");
  t->Add("loop_closure_unknown_probability", &c.matcher.unknown_probability,
         "what an endpoint in a never-observed cell scores in the search");
  t->Add("loop_closure_ambiguity_ratio", &c.matcher.ambiguity_ratio,
         "refuse a match when another place scores this fraction of it (0: no check)");
  t->Add("loop_closure_peak_radius", &c.matcher.peak_radius,
         "poses this close to the best (m) belong to its peak, not another place");
  t->Add("loop_closure_peak_angle", &c.matcher.peak_angle,
         "headings this close to the best (rad) belong to its peak");
  mapping::PoseGraphOptions& g = l->pose_graph;
  t->Add("pose_graph_local_translation_weight", &g.local_translation_weight,
         "weight of the front end's node-in-submap constraints, translation (1/m)");
  t->Add("pose_graph_local_rotation_weight", &g.local_rotation_weight,
         "weight of the front end's node-in-submap constraints, rotation (1/rad)");
  t->Add("loop_closure_translation_weight", &g.loop_translation_weight,
         "weight of loop constraints, translation (1/m)");
  t->Add("loop_closure_rotation_weight", &g.loop_rotation_weight,
         "weight of loop constraints, rotation (1/rad)");
  t->Add("pose_graph_consecutive_translation_weight", &g.consecutive_translation_weight,
         "weight of the front end's motion between consecutive nodes, translation (1/m)");
  t->Add("pose_graph_consecutive_rotation_weight", &g.consecutive_rotation_weight,
         "weight of the front end's motion between consecutive nodes, rotation (1/rad)");
  t->Add("loop_closure_huber_scale", &g.huber_scale,
         "Huber loss scale on loop constraints' weighted residuals (0: least squares)");
  t->Add("pose_graph_slip_distance", &g.slip_distance,
         "a node two independent loop constraints agree on, within this (m), and put farther "
         "than this from the solution is slipped: its local and consecutive constraints become "
         "robust from then on (0: never)");
  t->Add("pose_graph_slip_angle", &g.slip_angle,
         "... and within this angle (rad) of each other");
  t->Add("pose_graph_max_num_iterations", &g.max_num_iterations,
         "Ceres iterations per optimisation");
  t->Add("loop_closure_optimize_every_n_nodes", &l->optimize_every_n_nodes,
         "optimise the pose graph after this many new nodes");
  t->Add("loop_closure_live_map", &l->live_map,
         "add every inserted scan to the global map at once, between its redraws (false: only "
         "redraws)");
  t->Add("loop_closure_restart_after_lost_scans", &l->restart_after_lost_scans,
         "lost for this many matched scans over which odometry moved the robot (not standing or "
         "turning on the spot), the front end starts a new submap at odometry's pose (0: never; "
         "lost stays lost until relocalized)");
  t->Add("loop_closure_odometry_confirms_distance", &l->odometry_confirms_distance,
         "a match scored below tracking_ok_score (not failed) still goes into the active submap "
         "when it lies within this (m) of odometry's prediction (0: never)");
  t->Add("loop_closure_odometry_confirms_angle", &l->odometry_confirms_angle,
         "... and within this (rad) of its heading");
  t->Add("loop_closure_max_queued_submaps", &l->max_queued_submaps,
         "the scan path waits while this many finished submaps wait for the worker (0: never)");
  t->Add("loop_closure_max_queued_submap_pyramids", &l->max_queued_submap_pyramids,
         "of the finished submaps waiting for the worker, at most this many keep their grids; "
         "later ones are drawn again from their nodes when searched (-1: all keep them)");
  t->Add("loop_closure_worker_niceness", &l->worker_niceness,
         "nice increment of the loop-closure worker thread over the scan path's (0-19)");
  t->Add("loop_closure_worker_idle_priority", &l->worker_idle_priority,
         "runs the worker only on cores nothing else wants (Linux SCHED_IDLE; instead of the "
         "niceness): a waking scan takes its core at once, but on a machine kept busy it nearly "
         "stops");
}

}  // namespace

ParameterTable SlamParameterTable(SlamOptions* o) {
  ParameterTable t;
  t.Add("lattice", &o->lattice, "cell shape: hex (this method) or square (hector's baseline)");
  t.Add("map_resolution", &o->map_resolution,
        "finest cell size in m: hex centre spacing d, or square side");
  t.Add("map_size", &o->map_size, "initial map storage, cells per side");
  t.Add("map_start_x", &o->map_start_x, "origin position in the initial map, fraction of width");
  t.Add("map_start_y", &o->map_start_y, "origin position in the initial map, fraction of height");
  t.Add("map_multi_res_levels", &o->map_multi_res_levels, "pyramid levels, cell area x4 each");
  t.Add("map_max_coarse_resolution", &o->map_max_coarse_resolution,
        "levels whose cells would be larger than this (m) are not built; 0: no limit");
  t.Add("map_min_coarse_resolution", &o->map_min_coarse_resolution,
        "levels are added until the coarsest cell is at least this size (m); 0: exactly "
        "map_multi_res_levels");
  t.Add("update_factor_free", &o->update_factor_free, "occupancy a pass-through implies");
  t.Add("update_factor_occupied", &o->update_factor_occupied, "occupancy a hit implies");
  t.Add("map_update_distance_thresh", &o->map_update_distance_thresh,
        "update the map after moving this far (m)");
  t.Add("map_update_angle_thresh", &o->map_update_angle_thresh,
        "update the map after turning this much (rad)");
  t.Add("map_update_score_margin", &o->map_update_score_margin,
        "also update the map when the match's score has sunk to within this of "
        "tracking_ok_score (0: off)");
  t.Add("map_update_min_distance", &o->map_update_min_distance,
        "... once this far (m) from the last update");
  t.Add("map_with_known_poses", &o->map_with_known_poses,
        "skip matching and map at the odometry poses");
  t.Add("update_map", &o->update_map,
        "false: localization only, matching against a fixed (loaded) map");
  t.Add("predict_constant_velocity", &o->predict_constant_velocity,
        "without odometry, predict each pose from the previous scan's motion");
  t.Add("constant_velocity_horizon", &o->constant_velocity_horizon,
        "without odometry, scans not matched are extrapolated at most this long (s) after the "
        "last match; then the pose holds still");
  t.Add("map_auto_grow", &o->map_auto_grow, "grow the map when scans reach its edge");
  t.Add("map_max_cells", &o->map_max_cells,
        "cap on cells per pyramid level (at most " + std::to_string(kMaxMapCells) + ")");
  t.Add("odometry_jump_distance_thresh", &o->odometry_jump_distance_thresh,
        "odometry moving farther than this (m) between scans is a fault: increment dropped");
  t.Add("odometry_jump_angle_thresh", &o->odometry_jump_angle_thresh,
        "odometry turning more than this (rad) between scans is a fault (pi: never)");
  t.Add("log_odds_limit", &o->log_odds_limit, "clamp on a cell's log-odds magnitude");
  t.Add("laser_min_dist", &o->laser_min_dist, "ignore returns nearer than this (m)");
  t.Add("laser_max_dist", &o->laser_max_dist, "ignore returns farther than this (m)");
  t.Add("laser_range_max_is_no_return", &o->laser_range_max_is_no_return,
        "a reading at the scan's range_max is a beam without a return, not a hit");
  t.Add("laser_range_max_margin", &o->laser_range_max_margin,
        "with laser_range_max_is_no_return, so is a reading less than this short of range_max (m)");
  t.Add("laser_z_min_value", &o->laser_z_min_value,
        "a tilted laser's points lower than this above the laser are ignored (m)");
  t.Add("laser_z_max_value", &o->laser_z_max_value,
        "a tilted laser's points higher than this above the laser are ignored (m)");
  t.Add("laser_match_max_incidence", &o->laser_match_max_incidence,
        "endpoints whose beam meets a straight surface farther than this from its normal (rad) "
        "are inserted, not matched (pi/2: off)");
  t.Add("min_valid_beams", &o->min_valid_beams,
        "match only scans with at least this many matchable beams");
  ScanMatcherOptions& m = o->matcher;
  t.Add("scan_match_max_iterations_coarse", &m.max_iterations_coarse,
        "Gauss-Newton iterations on each coarse level");
  t.Add("scan_match_max_iterations_fine", &m.max_iterations_fine,
        "Gauss-Newton iterations on the finest level");
  t.Add("scan_match_translation_tolerance_cells", &m.translation_tolerance_cells,
        "converged when a step moves less than this many cells");
  t.Add("scan_match_angle_tolerance", &m.angle_tolerance,
        "converged when a step turns less than this (rad)");
  t.Add("scan_match_max_angle_step", &m.max_angle_step, "largest rotation per iteration (rad)");
  t.Add("scan_match_max_translation_step_cells", &m.max_translation_step_cells,
        "largest translation per iteration, in cells of the level");
  t.Add("scan_match_coarse_point_spacing_cells", &m.coarse_point_spacing_cells,
        "merge endpoints closer than this many cells on coarse levels");
  t.Add("scan_match_subcell_offsets", &m.subcell_offsets,
        "match against where in each cell its hits fell (off: the paper's / hector's method)");
  t.Add("scan_match_verify_converged_step", &m.verify_converged_step,
        "check the cost after a step within the tolerances too (on: hector's method as run here)");
  t.Add("scan_match_angle_tolerance_from_range", &m.angle_tolerance_from_range,
        "angle tolerance = translation tolerance / mean range (off: hector's method as run here)");
  t.Add("scan_match_coarsest_min_move_cells", &m.coarsest_min_move_cells,
        "drop coarsest-level moves below this many of its cells (0, the default: keep all)");
  t.Add("scan_match_robust_loss_scale", &m.robust_loss_scale,
        "Cauchy loss scale on the residual 1 - M: endpoints the map does not explain lose "
        "weight (0: plain least squares)");
  t.Add("scan_match_odometry_translation_weight", &m.odometry_translation_weight,
        "pull of odometry's predicted position on the match, per endpoint and m² (0: off, as "
        "hector)");
  t.Add("recovery_score_ratio", &o->recovery_score_ratio,
        "search for a lost pose when a match scores below this fraction of recent ones (0: off)");
  t.Add("recovery_linear_window", &o->recovery.linear_window,
        "recovery search half-width in x and y (m)");
  t.Add("recovery_angular_window", &o->recovery.angular_window,
        "recovery search half-width in heading (rad)");
  t.Add("recovery_wide_linear_window", &o->recovery_wide_linear_window,
        "second, wider recovery search half-width in x and y (m), when the first fails");
  t.Add("recovery_wide_angular_window", &o->recovery_wide_angular_window,
        "second, wider recovery search half-width in heading (rad, at most pi; 0 with the "
        "linear one: no second search)");
  t.Add("recovery_wide_collapse_ratio", &o->recovery_wide_collapse_ratio,
        "without odometry, take the wide search's pose beyond the first window when the match's "
        "share of endpoints on known cells fell below this fraction of the previous scan's and "
        "the map agrees with the search's pose (0: off)");
  t.Add("prediction_acc_lim_x", &o->prediction_acc_lim_x,
        "without odometry: the platform's linear acceleration limit (m/s^2); a scan whose "
        "prediction may be off by more than a search step also searches that far (0: never)");
  t.Add("prediction_acc_lim_theta", &o->prediction_acc_lim_theta,
        "without odometry: the platform's angular acceleration limit (rad/s^2)");
  t.Add("recovery_step_cells", &o->recovery.step_cells,
        "recovery search translation step, in cells of the coarsest level");
  t.Add("recovery_point_spacing_cells", &o->recovery.point_spacing_cells,
        "recovery search merges endpoints closer than this many coarsest cells");
  t.Add("recovery_max_candidates", &o->recovery.max_candidates,
        "recovery search scores at most this many poses; a larger window is refused");
  TrackingOptions& k = o->tracking;
  t.Add("tracking_ok_score", &k.ok_score,
        "a match is good when this fraction of its endpoints on mapped cells hit occupied ones");
  t.Add("tracking_lost_score", &k.lost_score,
        "a match scoring below this failed: its pose is not used");
  t.Add("tracking_lost_after_scans", &k.lost_after_scans,
        "this many failed (or, without odometry, blind) scans in a row: lost");
  t.Add("tracking_ok_after_scans", &k.ok_after_scans,
        "this many good matches in a row bring the state back to ok");
  t.Add("tracking_min_known_fraction", &k.min_known_fraction,
        "a match with a smaller fraction of its endpoints on mapped cells is not scored");
  t.Add("tracking_lost_search_linear_window", &k.lost_search_linear_window,
        "while lost, search this far (m) around the prediction in x and y");
  t.Add("tracking_lost_search_angular_window", &k.lost_search_angular_window,
        "while lost, search this far (rad) around the predicted heading (pi: all)");
  t.Add("tracking_lost_search_odometry_angular_window", &k.lost_search_odometry_angular_window,
        "while lost with odometry, search at most this far (rad) around odometry's heading");
  t.Add("tracking_lost_search_odometry_turn_fraction", &k.lost_search_odometry_turn_fraction,
        "... plus this fraction of odometry's turning since the robot was lost");
  t.Add("tracking_lost_search_max_candidates", &k.lost_search_max_candidates,
        "while lost, each scan's search scores at most this many poses (sectors over scans)");
  AddGlobalLocalizationParameters(&o->global_localization, &t);
  AddLoopClosureParameters(&o->loop_closure, &t);
  return t;
}

}  // namespace hex_slam
