// How far the SLAM estimate can be trusted: a score per match, and a tracking state (ok /
// degraded / lost) kept with hysteresis over the scans. ROS-free: Slam keeps one, the node
// publishes it on /diagnostics and on a latched topic, the offline tools count it.
//
// A scan matcher always returns a pose, and the residual-based covariance of a wrong local
// minimum is as tight as that of the right one (a localization started 46° off ended 10.7 m
// off with σ 4–6 mm). What tells them apart is the map itself: at the right pose the endpoints
// fall on cells the map knows to be occupied; at a wrong one many fall on cells it knows to be
// free.
#ifndef HEX_SLAM_MAPPING_TRACKING_STATE_H_
#define HEX_SLAM_MAPPING_TRACKING_STATE_H_

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {

enum class TrackingState {
  kOk,        // the matches agree with the map: the pose and its covariance can be used
  kDegraded,  // some scans did not (poor or blind scans, an unconfirmed pose): use with care
  kLost,      // the matches contradict the map: the pose is not known; searching for it
};

const char* TrackingStateName(TrackingState state);

struct TrackingOptions {
  // A match is good when at least this fraction of its endpoints that fall on cells the map
  // knows fall on occupied ones (MatchScore); good matches bring the state back to ok.
  double ok_score = 0.8;
  // A match scoring below this failed: its pose is not used (the prediction is kept), and
  // lost_after_scans failures in a row (without a good match between) mean the robot is lost.
  double lost_score = 0.7;
  int lost_after_scans = 5;
  // Good matches in a row that bring a degraded or lost state back to ok.
  int ok_after_scans = 3;
  // A score needs at least this fraction of the endpoints on cells the map knows (occupied, or
  // confidently free); less (a scan of unmapped space, a pose off the map seeing the outside of
  // its walls) leaves the match unscored: used while tracking, but it cannot confirm a pose.
  double min_known_fraction = 0.5;
  // While lost, each scan searches this window around the prediction (m on each side in x and y;
  // rad on each side in heading, pi: every heading) with the recovery search's step and budget
  // (recovery_max_candidates). A window over the budget is searched in heading sectors, one
  // per scan, round-robin.
  double lost_search_linear_window = 1.0;
  double lost_search_angular_window = M_PI;
  // With odometry, the heading window is at most this plus turn_fraction of the turning odometry
  // has measured since the robot was lost: a wheel's heading drifts by a few percent of its turns,
  // so a place at a heading odometry rules out is a likeness, not the robot (MIT Killian with
  // map_update_angle_thresh 0.85, lost for three scans in a corridor, relocalized turned by pi
  // and mapped the rest of the log backwards: 11.41 m relations error, 0.630 m with the bound).
  // Without odometry every heading stays open.
  double lost_search_odometry_angular_window = 0.5;
  double lost_search_odometry_turn_fraction = 0.1;
  // The most poses one scan's search while lost may score (at most recovery_max_candidates); a
  // wider window is covered over several scans. 200,000 (every heading of the default window at
  // once, the search now a branch and bound) was tried: ACES without odometry 0.0445 -> 0.0439 m,
  // MIT Killian without odometry 17.9 -> 22.7 m (lost either way), the hospital unchanged.
  int lost_search_max_candidates = 20000;

  // Empty when valid; otherwise one message per bad field, naming its parameter.
  std::vector<std::string> Validate() const;
};

// How well a scan at a pose agrees with the map.
struct MatchScore {
  int points = 0;     // endpoints scored
  int known = 0;      // of them, on cells the map holds occupied or confidently free
  int agreeing = 0;   // of those, on occupied ones
  // agreeing / known; NaN (unscored) when known < min_known_fraction × points.
  double score = std::numeric_limits<double>::quiet_NaN();
  // agreeing / known whatever the fraction, when at least the minimum count is known: how the
  // part of a scan of mostly unmapped space that is on the map agrees with it. NaN otherwise.
  double known_agreement = std::numeric_limits<double>::quiet_NaN();
  bool scored() const { return !std::isnan(score); }
  // The share of the endpoints on known cells (0 for none scored).
  double known_fraction() const { return points > 0 ? static_cast<double>(known) / points : 0.0; }
};

// Scores `points` (base frame) at `pose` on `grid`: each endpoint's cell, no interpolation. Slam
// scores on the pyramid's second level (cells twice the finest), so that an endpoint a finest
// cell off its wall (range noise, a wall seen at a grazing angle) still agrees.
template <class Lattice>
MatchScore ScoreMatch(const GridMap<Lattice>& grid, const std::vector<Eigen::Vector2d>& points,
                      const Pose2& pose, double min_known_fraction, int min_known_points);

// What one scan says about the estimate.
enum class ScanEvidence {
  kGood,          // a match scoring at least ok_score
  kPoor,          // scored between lost_score and ok_score, or unscored
  kFailed,        // scored below lost_score, or not finite
  kBlind,         // too few returns to match, and no odometry: nothing measured the motion
  kOdometryOnly,  // too few returns to match; odometry carried the pose
  kUnconfirmed,   // the pose was set from outside (initialpose, a loaded map)
};

// The state machine. Hysteresis: one poor or failed scan degrades an ok state, lost_after_scans
// failed (or blind) scans in a row lose it, and only ok_after_scans good matches in a row restore
// ok, so the state does not flicker on a noisy score.
class TrackingMonitor {
 public:
  explicit TrackingMonitor(const TrackingOptions& options) : options_(options) {}

  // Takes one scan's evidence (`score`: its match's, NaN when none). Returns true when the state
  // changed; reason() then says why.
  bool Update(ScanEvidence evidence, double score);
  // Back to ok (a fresh map: the first scan defines the pose).
  void Reset();
  // Straight to lost (the estimate was poisoned); true when that changed the state.
  bool Lose(const std::string& reason);
  // Degraded, counting afresh: the front end started over on a new submap after being lost.
  void StartOver(const std::string& reason);

  TrackingState state() const { return state_; }
  const std::string& reason() const { return reason_; }
  int failed_in_a_row() const { return failed_in_a_row_; }
  int good_in_a_row() const { return good_in_a_row_; }

 private:
  bool Enter(TrackingState state, const std::string& reason);

  TrackingOptions options_;
  TrackingState state_ = TrackingState::kOk;
  std::string reason_ = "started";
  int failed_in_a_row_ = 0;
  int good_in_a_row_ = 0;
};

// Classifies a match by its score and whether its pose is finite. An unscored match (most
// endpoints off the map) fails on a fixed map (localization: the pose is off the map, or the
// robot left it); while the map can grow to take them (`map_grows`: exploring) it is judged by
// the part on the map: failed below lost_score, else poor.
ScanEvidence MatchEvidence(const TrackingOptions& options, const MatchScore& score, bool finite,
                           bool map_grows);

}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_TRACKING_STATE_H_
