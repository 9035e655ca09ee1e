// Every parameter of the SLAM processor, with hector_mapping's names and defaults where the
// concept is the same. map_resolution is the hex centre spacing d (the square side on the square
// lattice); equal cell area means d = s·sqrt(2/sqrt(3)) ≈ 1.0746·s.
#ifndef HEX_SLAM_MAPPING_SLAM_OPTIONS_H_
#define HEX_SLAM_MAPPING_SLAM_OPTIONS_H_

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "hex_slam/matching/correlative_search.h"
#include "hex_slam/map/grid_map.h"
#include "hex_slam/mapping/global_localizer.h"
#include "hex_slam/mapping/loop_closure/loop_closure_options.h"
#include "hex_slam/common/parameter_table.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/mapping/tracking_state.h"

namespace hex_slam {

// The most pyramid levels map_multi_res_levels may ask for, or the coarse-cell minimum may add.
constexpr int kMaxMapLevels = 8;
// The hard limit on map_max_cells: 134 million cells per level (about 3.7 GB for the finest;
// 580 m x 580 m at 5 cm). Beyond it a dense grid is the wrong tool, and cell indices stay far
// inside int's range (grid_index.h).
constexpr std::int64_t kMaxMapCells = std::int64_t{1} << 27;

struct SlamOptions {
  std::string lattice = "hex";  // "hex" or "square" (the hector_mapping baseline)

  // Map (hector_mapping names and defaults, except map_resolution: hector's 0.025 m with three
  // levels leaves a coarsest cell of 0.1 m, too small a basin for 5 Hz logs without odometry;
  // 0.05 m gives 0.2 m and loses little accuracy, see docs).
  double map_resolution = 0.05;
  // Initial storage, cells per side; the map grows beyond it. Storage costs memory only where
  // the robot has seen, so a large map_size (hector's launch files use 2048) is cheap.
  int map_size = 1024;
  double map_start_x = 0.5;  // where the origin sits in the initial storage, as a fraction
  double map_start_y = 0.5;
  int map_multi_res_levels = 3;  // built exactly, unless one of the two limits below is set
  // Levels whose cells would exceed this size are not built: a coarse cell as wide as a corridor
  // smears the walls together and leads the finer levels astray (0.2 m cells in a 0.9 m maze
  // lose the robot with three levels, not with two). 0: no limit.
  double map_max_coarse_resolution = 0.0;  // m
  // Levels are added beyond map_multi_res_levels until the coarsest cell is at least this size:
  // the coarsest cell is the basin Gauss–Newton converges from, and a 5 Hz log needs more than
  // 0.1 m of it (hector's 0.025 m cells on three levels leave 0.1 m and lose the Intel log
  // without odometry; four levels keep it, and three levels of 0.03 m cells, 0.12 m, do too).
  // 0.15 m would leave the 0.05 m default and its equal-area 0.0465 m square both on three
  // levels. 0 (the default) builds exactly map_multi_res_levels, as hector does; the node says
  // at start-up when the coarsest cell is smaller than that.
  double map_min_coarse_resolution = 0.0;  // m
  double update_factor_free = 0.4;
  double update_factor_occupied = 0.9;
  double map_update_distance_thresh = 0.4;  // m
  double map_update_angle_thresh = 0.9;     // rad
  // A scan is also inserted before those thresholds when its match's score has sunk to within
  // this margin above tracking_ok_score, once the robot is map_update_min_distance from the last
  // insertion (0: the thresholds only, as hector). Below tracking_ok_score no scan goes in (a
  // poor match must not draw the map), yet the score sinks as the robot drives away from where
  // the map was last drawn, fastest down a corridor whose walls ahead were seen only at grazing
  // angles (their cells read free at the scoring level). When the thresholds are reached only
  // after the score has crossed it, the map is never drawn again there: with hector's launch
  // file (0.06 rad) the Intel log was lost at 245 s with odometry, in 10 of 10 nudged runs.
  double map_update_score_margin = 0.05;
  double map_update_min_distance = 0.1;  // m
  bool map_with_known_poses = false;  // trust the odometry prior, skip matching
  // false: localization on a fixed map (one loaded from a .hexmap file, or else the first scan's):
  // scans are matched, the map is never changed.
  bool update_map = true;
  // Without odometry, start matching from the previous pose moved by the previous scan's motion
  // (hector starts from the previous pose itself).
  bool predict_constant_velocity = true;
  // ... but blind scans (too few returns) only over a short horizon: the scan after a matched
  // one is always predicted; blind scans are extrapolated only this long (s) after the last
  // match, and then the pose holds still. A robot that goes blind and stops is not pushed on by
  // its last velocity (60 blind scans moved a standing robot 1.8 m). Over failed matches the
  // prediction carries on until the state is lost: a scan that sees clutter is no sign of a stop.
  double constant_velocity_horizon = 0.2;  // s
  // Odometry that moves farther (m) or turns more (rad) between two consecutive scans than this
  // is a fault (a wrapped counter, a reset driver, a corrupt message), not motion: the increment
  // is dropped, the scan is matched as if it had no odometry, and the next increment is measured
  // from this odometry. Subsampled logs move ~0.3 m and turn up to ~2 rad between scans; pi, the
  // angle's default, never triggers (any heading change is a plausible turn).
  double odometry_jump_distance_thresh = 10.0;  // m
  double odometry_jump_angle_thresh = M_PI;     // rad

  // Map growth and cell limits (hector's map is fixed; ours grows).
  bool map_auto_grow = true;
  // Per level: 16.8 million cells, 200 m x 200 m of 5 cm squares (~450 MB for the finest level's
  // storage). At most kMaxMapCells.
  std::int64_t map_max_cells = std::int64_t{1} << 24;
  double log_odds_limit = 50.0;  // hector caps occupied cells at 50

  // Beams (hector_mapping names and defaults).
  double laser_min_dist = 0.4;
  double laser_max_dist = 30.0;
  // A reading at the scan's range_max, or less than laser_range_max_margin short of it, is no
  // return, not a hit (RangeFilter::range_max_is_no_return). hector_mapping drops 0.1 m; 0 here:
  // with a 4 m lidar in the 10 m test room that margin doubles the error (its real walls at
  // 3.9-4 m go), so set it for a sensor whose no-return readings fall short of range_max.
  bool laser_range_max_is_no_return = true;
  double laser_range_max_margin = 0.0;  // m
  // A tilted laser's points count only if their height above the laser (base frame z) lies in
  // (laser_z_min_value, laser_z_max_value); a level laser's are all at height 0.
  double laser_z_min_value = -1.0;  // m
  double laser_z_max_value = 1.0;   // m
  // Endpoints whose beam meets a straight surface more than this far from its normal (rad) are
  // inserted but not matched (sensor/grazing_endpoints.h: matched, the dotted walls such beams
  // leave in a submap can pull a scan back along a corridor to the last inserted scan's pose).
  // π/2, the default: every endpoint is matched, as hector does. 80° (1.3962634) holds the simulated
  // building without odometry on every seed (lost on 2 of 4 without it) and is neutral on Intel
  // with odometry and on the paper's rows, but loses Intel without odometry on hector's 0.025 m
  // square cells and at 2 Hz, where the grazing returns' pull along the walls is what holds the
  // scan (docs/ros.md, "Grazing endpoints"): for long, bare corridors without odometry.
  double laser_match_max_incidence = 0.5 * M_PI;  // rad
  // Fewer matchable endpoints than this and the scan is not matched (the pose follows odometry).
  int min_valid_beams = 20;

  ScanMatcherOptions matcher;

  // Recovery: when a match's score (mean occupancy at the endpoints) falls below this fraction of
  // the recent average, search a window around the prediction on the coarsest level and match
  // again from the best pose found; the better of the two results is kept. 0 disables.
  double recovery_score_ratio = 0.75;
  CorrelativeSearchOptions recovery;
  // When the match from the window's best pose still scores below that fraction, a second search
  // with these half-widths (same steps and recovery_max_candidates budget) around the prediction:
  // steps of 0.3 m and turns of 2 rad between scans (a subsampled log, no odometry) that the
  // constant-velocity prediction did not foresee. 0 for both: no second search.
  double recovery_wide_linear_window = 0.8;    // m
  double recovery_wide_angular_window = M_PI;  // rad: every heading
  // Without odometry, a robot that turns (or moves) faster than the prediction and the first
  // window reach leaves its match on a pose where most of the scan falls on unknown cells: too
  // few to score it, so neither that match nor the wide search's right pose, which sees as
  // little of the map after a fast turn with a 180° lidar, can convince the tracking score. The
  // wide search's pose is then taken when (a) the match collapsed, its share of endpoints on
  // known cells falling below this fraction of the previous scan's (driving into new space
  // lowers it gradually, losing the scan at once), (b) the pose lies beyond the first window,
  // and (c) there the part of the scan on the map agrees (tracking_ok_score) with more than
  // twice as many endpoints as at the match. 0: off.
  double recovery_wide_collapse_ratio = 0.5;
  // Without odometry the constant-velocity prediction is off by as much as the platform can
  // change its velocity between scans: up to a·Δt² over the Δt since the last match, for its
  // linear and angular acceleration limits (move_base's acc_lim_x, acc_lim_theta). Gauss–Newton
  // converges from about a coarsest cell of the truth; from farther it can stop on a wrong optimum
  // that fits as well (in a corridor, a step short of where the robot is), so a low score never
  // flags it. When that bound moves the mean endpoint more than the first recovery window's step,
  // each such scan also searches the bound around the prediction (at most the first recovery
  // window, `recovery`) on the coarsest level, matches from the best pose if it lies in another
  // basin, and keeps whichever match the search's own score (CorrelativeScore) prefers. The
  // window follows the scan rate: a 40 Hz lidar's is under a millimetre and nothing is searched;
  // a log subsampled to 1 Hz searches the whole first window. 0 for both: never.
  double prediction_acc_lim_x = 1.0;      // m/s²
  double prediction_acc_lim_theta = 2.0;  // rad/s²

  // The tracking state (ok / degraded / lost) and the search while lost: tracking_state.h.
  TrackingOptions tracking;

  // While lost on a loaded map (update_map false), or while it does not confirm the pose it was
  // given: a branch-and-bound search over the whole map (mapping/global_localizer.h).
  mapping::GlobalLocalizationOptions global_localization;

  // Submaps, loop constraints and the pose graph (on by default; off is the incremental SLAM
  // of one global map, hector's way). Only with update_map.
  mapping::LoopClosureOptions loop_closure;

  // Empty when valid; otherwise one message per bad field, naming its parameter.
  std::vector<std::string> Validate() const;
};

// The world box the initial storage covers: map_size cells per side with the origin at
// (map_start_x, map_start_y) of it.
Eigen::AlignedBox2d InitialMapExtent(const SlamOptions& options);

// map_multi_res_levels, raised until the coarsest cell reaches map_min_coarse_resolution (at most
// kMaxMapLevels), then reduced so no level's cells exceed map_max_coarse_resolution (at least 1).
int EffectiveLevels(const SlamOptions& options);

// The map's cell update model and growth policy, from the options (what Slam's pyramid is built
// with; a copy drawn elsewhere, e.g. the node's redrawn map, uses the same).
OccupancyModel MapOccupancyModel(const SlamOptions& options);
GridGrowthPolicy MapGrowthPolicy(const SlamOptions& options);

// The table binding each parameter name to its field in `options`.
ParameterTable SlamParameterTable(SlamOptions* options);

}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_SLAM_OPTIONS_H_
