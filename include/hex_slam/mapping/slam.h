// The SLAM processor: scans in, poses out, map kept. ROS-free; the node and the offline tools are
// thin adapters around it (as hector's HectorSlamProcessor under its node).
//
// Not thread-safe by itself: callers that read the map from another thread hold one lock around
// every call (the node does), and copy what they publish under it.
//
// With loop closure (options().loop_closure.enabled, on by default, and update_map) the front
// end matches against and inserts into submaps (mapping::LoopClosure) instead of one map, every
// inserted scan becomes a node, and a background worker searches loop constraints and optimises
// the pose graph. The tracking state and the recovery judge matches on the active submap. pose() stays the front end's estimate in its own (local) frame; the optimised poses and
// the correction from it to the map frame are on solutions(), readable from any thread.
// hex_maps()/square_maps() then hold the global map: as RefreshGlobalMap() last drew it from the
// nodes at their optimised poses, plus (loop_closure_live_map) every scan inserted since, at its
// pose in the map frame. A publisher that would rather not hold the lock while the map is drawn
// copies Nodes() and solutions()->Get() and calls mapping::DrawGlobalMap on its own pyramid.
#ifndef HEX_SLAM_MAPPING_SLAM_H_
#define HEX_SLAM_MAPPING_SLAM_H_

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/matching/hex_scan_matcher.h"
#include "hex_slam/sensor/laser_scan.h"
#include "hex_slam/matching/match_covariance.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/mapping/loop_closure/loop_closure.h"
#include "hex_slam/geometry/pose2.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/sensor/scan_sanitizer.h"
#include "hex_slam/sensor/sensor_mount.h"
#include "hex_slam/mapping/slam_options.h"
#include "hex_slam/matching/square_scan_matcher.h"
#include "hex_slam/mapping/tracking_state.h"

namespace hex_slam {

enum class ScanOutcome {
  kMatched,            // matched against the map; the pose is the match
  kInitialized,        // the first scan: it seeded the map at the start pose
  kKnownPose,          // map_with_known_poses: the pose is the odometry's
  kInvalidScan,        // malformed (see message); nothing changed
  kTooFewPoints,       // too few valid beams to match; the pose followed odometry, if any
  kTimeWentBackwards,  // stamped before the previous scan; nothing changed
};

const char* ScanOutcomeName(ScanOutcome outcome);

struct ScanReport {
  ScanOutcome outcome = ScanOutcome::kInvalidScan;
  // Why the scan was not used; for a used one, what went wrong on the way (an odometry fault, a
  // refused recovery search). Several are joined with "; ".
  std::string message;
  Pose2 pose;  // the estimate after this scan (base frame in the map frame)
  // The pose's covariance (m², rad²): the match's (match_covariance.h) when this scan's match
  // placed the robot and the state is not lost; otherwise nothing measured the pose, and every
  // direction is unconstrained (UnknownPoseCovariance). Its axes are global_pose's (the map
  // frame's; the same as pose's without loop closure).
  Eigen::Matrix3d covariance = UnknownPoseCovariance();
  // The pose is this scan's match (or the first scan's, which defines the map), not a prediction
  // carried over a scan that could not be matched or whose match failed.
  bool pose_from_scan = false;
  // Too little of the scan on the map to judge its match, so odometry's prediction is the pose
  // (pose_from_scan is false) and, while mapping, the scan is inserted there: a robot that
  // drove into unmapped space between two scans maps it as it goes.
  bool placed_by_odometry = false;
  bool map_updated = false;
  // ProcessScan with defer_map_update: the scan goes into the map at InsertDeferredScan (or at
  // the next ProcessScan), not yet; map_updated, updated_region and node_id are set then.
  bool map_update_deferred = false;
  // With map_updated: the world box of the scan's rays, outside which no cell changed.
  Eigen::AlignedBox2d updated_region;
  bool recovered = false;  // the recovery search replaced Gauss–Newton's result
  // The odometry was not used: it jumped past odometry_jump_distance_thresh / _angle_thresh, or
  // was not finite (see message). The scan was matched without a prior.
  bool odometry_fault = false;
  BeamCounts beams;
  MatchResult match;  // valid when outcome == kMatched
  // With loop closure: the node this scan became when it was inserted (-1 otherwise), and the
  // pose moved into the map frame by the latest optimisation's correction (= pose without).
  int node_id = -1;
  Pose2 global_pose;

  // How far the estimate can be trusted after this scan (tracking_state.h).
  TrackingState tracking_state = TrackingState::kOk;
  bool tracking_changed = false;  // this scan changed it: tracking_reason says why
  std::string tracking_reason;
  ScanEvidence evidence = ScanEvidence::kPoor;  // what this scan said about the estimate
  MatchScore score;  // the match's agreement with the map (kMatched only)
  // While lost, the wide search found a pose the map agrees with, and the pose jumped there.
  bool relocalized = false;
  // ... found by the search over the whole loaded map (global_localization), while lost or
  // while the scans did not confirm the pose the robot was given on it.
  bool relocalized_globally = false;
};

class Slam {
 public:
  // Throws std::invalid_argument listing every problem Validate() finds.
  explicit Slam(const SlamOptions& options);
  ~Slam();

  // `mount`: the laser on the base at the scan's stamp. `odometry`: the base's odometry pose at
  // the scan's stamp, if known; the motion since the previous one seeds the matcher.
  // With defer_map_update, a scan that goes into the map is only noted (map_update_deferred):
  // a live caller publishes the pose first and inserts it after (InsertDeferredScan), so the
  // insertion, and with loop closure the node and submap bookkeeping, stay off the pose's
  // latency. The map and pose are the same either way.
  ScanReport ProcessScan(const LaserScan& scan, const SensorMount& mount,
                         const std::optional<Pose2>& odometry = std::nullopt,
                         bool defer_map_update = false);
  // A level laser at `sensor_pose` on the base.
  ScanReport ProcessScan(const LaserScan& scan, const Pose2& sensor_pose = Pose2(),
                         const std::optional<Pose2>& odometry = std::nullopt) {
    return ProcessScan(scan, SensorMount(sensor_pose), odometry);
  }

  // Inserts the scan the last ProcessScan deferred, at the pose it was matched at, and sets
  // `report`'s map_updated, updated_region and node_id. False when there is none: none was
  // deferred, it is in already, or the pose or map changed since (Reset, SetPose, a loaded map),
  // which drops it.
  bool InsertDeferredScan(ScanReport* report);

  // Forgets the map and restarts at `pose`.
  void Reset(const Pose2& pose = Pose2());
  // Moves the estimate to `pose` in the map frame (e.g. rviz's initialpose; with loop closure
  // GlobalPose() becomes `pose`); the map is kept. A pose OutOfReach names is
  // refused (false, nothing changed): a non-finite one would poison every later match, a far one
  // would grow the map across the distance or match against nothing.
  bool SetPose(const Pose2& pose);
  // Empty when the robot may be placed at `pose`; otherwise why not: the pose is not finite, or it
  // lies farther than laser_max_dist from every cell the map knows (its scans could not see the
  // map), or the map could not grow to hold its scans within map_max_cells.
  std::string OutOfReach(const Pose2& pose) const;

  const Pose2& pose() const { return pose_; }
  const SlamOptions& options() const { return options_; }
  int scans_processed() const { return scans_processed_; }
  int map_updates() const { return map_updates_; }
  int recoveries() const { return recoveries_; }
  int odometry_faults() const { return odometry_faults_; }
  TrackingState tracking_state() const { return tracking_.state(); }
  // Why the state is what it is (the last change's reason).
  const std::string& tracking_reason() const { return tracking_.reason(); }
  int times_lost() const { return times_lost_; }
  // Times the front end started over on a new submap after being lost (loop closure only).
  int restarts() const { return restarts_; }
  int relocalizations() const { return relocalizations_; }
  // The searches over the whole loaded map so far (zeros without one).
  mapping::GlobalLocalizationStats global_localization_stats() const;
  // Blocks until a running whole-map search has finished; the next scan takes its result. For
  // tests and tools that want results independent of timing.
  void WaitForGlobalLocalization();

  // Exactly one of these is non-null, by options().lattice.
  const MapPyramid<HexLattice>* hex_maps() const { return hex_maps_.get(); }
  const MapPyramid<SquareLattice>* square_maps() const { return square_maps_.get(); }
  // For filling the map from outside (io::RestoreSlamMap loads a .hexmap file); call
  // UseLoadedMap() after, so the next scan is matched against it rather than seeding a new one.
  MapPyramid<HexLattice>* mutable_hex_maps() { return hex_maps_.get(); }
  MapPyramid<SquareLattice>* mutable_square_maps() { return square_maps_.get(); }
  // Marks the map as given: the pose stays (SetPose places the robot on it) and matching starts
  // with the next scan. Sub-cell hit offsets are not part of a loaded map, so matching on it uses
  // the plain interpolation until the map is updated.
  // The pose is unconfirmed on the loaded map until matches agree with it: the state is degraded.
  // With update_map false, scans that do not confirm it (or the robot lost on it) start a
  // search over the whole map (options().global_localization).
  // With loop closure on, mapping on from a loaded map goes on without it (the loaded map has no
  // submaps to close loops against).
  void UseLoadedMap();
  std::size_t MemoryBytes() const;

  // Loop closure is running: enabled, update_map, and no loaded map.
  bool loop_closure_active() const;
  // The worker's latest solution; the same board for the Slam's life (Reset publishes an empty
  // solution on it).
  const std::shared_ptr<mapping::LatestSolution>& solutions() const { return solutions_; }
  // The latest pose in the map frame: pose() moved by the latest correction.
  Pose2 GlobalPose() const;
  // The nodes so far (empty without loop closure).
  std::vector<std::shared_ptr<const mapping::TrajectoryNode>> Nodes() const;
  // The worker's figures (zeros without loop closure).
  mapping::LoopClosureStats loop_closure_stats() const;
  // Blocks: finishes the active submaps, waits until the worker has searched and optimised
  // everything, and redraws the global map. For the end of a log; scans processed after it
  // start new submaps.
  void FinishTrajectory();
  // FinishTrajectory without the redraw: the trajectory's optimised poses are final after it,
  // hex_maps()/square_maps() are not yet.
  void FinishLoopClosure();
  // Redraws hex_maps()/square_maps() from every node at the latest optimised poses (nothing to
  // do without loop closure, where they are the front end's map itself).
  void RefreshGlobalMap();

 private:
  bool ShouldUpdateMap() const;
  // The match's score is near the insertion gate (MapMayChange) away from the last insertion:
  // SlamOptions::map_update_score_margin.
  bool MapGoingStale(const ScanReport& report) const;
  // Returns the node the scan became with loop closure (-1 without); `region` gets the world box
  // of the rays inserted into hex_maps()/square_maps() (empty when they were not touched).
  int InsertIntoMap(const SensorMount& mount, double stamp, Eigen::AlignedBox2d* region);
  void StartLoopClosure();
  // The pyramid scans are matched against: the active submap's with loop closure.
  const MapPyramid<HexLattice>& HexMatchingMaps() const;
  const MapPyramid<SquareLattice>& SquareMatchingMaps() const;
  // `f` on the pyramid scans are matched against, whichever the lattice (f takes either).
  template <class F>
  auto OnMatchingMaps(F&& f) const {
    return hex_maps_ ? f(HexMatchingMaps()) : f(SquareMatchingMaps());
  }
  // base_points_ and insert_points_ from sensor_points_: onto the base's plane, within the
  // height limits; grazing endpoints only into insert_points_.
  void ToBasePoints(const SensorMount& mount, BeamCounts* beams);
  // Every endpoint of the scan, for the map and the nodes: base_points_ unless some grazing
  // ones were left out of them.
  const std::vector<Eigen::Vector2d>& InsertedPoints() const {
    return insert_points_.empty() ? base_points_ : insert_points_;
  }
  MatchResult Match(const Pose2& guess, GuessSource source = GuessSource::kPrediction) const;
  // Gauss–Newton from `guess`, then the recovery search if its score collapsed. `message` gets a
  // note when the search was refused (over its budget).
  // Whether the tracking score backs the recovery's `retry` (see MatchEvidence).
  bool MapSupports(const MatchResult& retry) const;
  // recovery_wide_collapse_ratio: the wide search's `retry` replaces a collapsed `match`.
  bool CollapsedMatchYields(const MatchResult& match, const MatchResult& retry) const;
  // `predicted_by_odometry`: the guess came from an odometry increment (no prediction search).
  MatchResult MatchWithRecovery(const Pose2& guess, bool predicted_by_odometry, bool* recovered,
                                std::string* message);
  // Replaces `result` by Gauss–Newton's match from one of AlternativePredictions when that
  // costs less, and then clears `recovered`: a prediction, not a search, placed the scan.
  void MatchAlternativePredictions(MatchResult* result, bool* recovered) const;
  // How far the no-odometry prediction may be off (SlamOptions::prediction_acc_lim_x), as a
  // search window; nullopt when that moves the mean endpoint (at `mean_range` from the base) no
  // more than one search step.
  std::optional<CorrelativeSearchOptions> PredictionWindow(double mean_range) const;
  // Replaces `result` by the match from the window's best pose when that lies in another basin
  // and the search's score prefers it.
  void SearchPredictionWindow(const Pose2& guess, const CorrelativeSearchOptions& window,
                              double mean_range, MatchResult* result, bool* recovered,
                              std::string* message) const;
  // The recovery search's translation step (m): recovery.step_cells coarsest cells.
  double RecoveryStep() const;
  // The recovery search's score of `pose` on the coarsest level (CorrelativeScore).
  double SearchScore(const Pose2& pose) const;
  CorrelativeResult SearchAround(const Pose2& centre, const CorrelativeSearchOptions& window) const;
  // The motion prior for a scan: the odometry's increment since the previous scan, or (none, or a
  // fault: report->odometry_fault) the no-odometry prediction.
  Pose2 PredictPose(const std::optional<Pose2>& odometry, ScanReport* report);

  // The tracking state (slam_tracking.cpp).
  // Without odometry: the previous motion again where PredictsMotion; the pose itself otherwise.
  // `stamp`: this scan's.
  Pose2 NoOdometryPrediction(double stamp) const;
  // Whether the no-odometry prediction at `stamp` carries the previous motion on: after a
  // matched scan, over failed matches until lost, over blind scans within
  // constant_velocity_horizon of the last match.
  bool PredictsMotion(double stamp) const;
  // Other no-odometry predictions worth a match, when the prediction carries motion: after a
  // recovery, the motion from before it (the jump mended the previous pose and is no velocity);
  // after scans went missing (scan_periods_ > 1), the motion once per scan period elapsed.
  std::vector<Pose2> AlternativePredictions(double stamp) const;
  // How many scan periods (the running average of the intervals) `interval` spans; 1 for a
  // gap longer than kMaxPredictedPeriods (slam_tracking.cpp): a stop, not dropped scans.
  int ScanPeriods(double interval) const;
  // Sets scan_periods_ for a scan stamped `stamp` and adds its interval to the average.
  void UpdateScanInterval(double stamp);
  // How the endpoints agree with the map at `pose` (tracking_state.h).
  MatchScore ScoreAt(const Pose2& pose) const;
  // While lost: the match from `guess`, and unless the map agrees with it, the match from the
  // best pose of a wide search around it (one heading sector per scan when over the budget).
  MatchResult MatchWhileLost(const Pose2& guess, bool odometry_predicted, ScanReport* report);
  // The whole-map search (a loaded map with update_map false): collects a finished search, or
  // starts one for this scan. The Gauss–Newton match from its pose carried to `guess`, when
  // the search was unambiguous (so `current`'s place scored well under it), its place is not
  // `current`'s, and the tracking score backs the match (MapSupports).
  std::optional<MatchResult> GlobalRelocalization(const Pose2& guess, const MatchResult& current,
                                                  ScanReport* report);
  // Whether a whole-map search can check the pose (a loaded map, not updated, searches on).
  bool CanCheckGlobally() const;
  // A loaded map's pose not yet confirmed: the whole-map search, even when this scan's match
  // looks good (a place that resembles another can score well at the wrong one); its match
  // replaces report->match when it finds a better place.
  void ConfirmLoadedPose(const Pose2& guess, ScanReport* report);
  CorrelativeResult SearchWhileLost(const Pose2& centre, bool odometry_predicted);
  double LostSearchAngularWindow(bool odometry_predicted) const;
  // Scores report->match and decides: its pose or the prediction `guess`, its covariance, the
  // state. `odometry_predicted`: the guess is odometry's, which stands for a scan of unmapped
  // space only (ScanReport::placed_by_odometry).
  void JudgeMatch(const Pose2& guess, bool odometry_predicted, ScanReport* report);
  void Track(ScanEvidence evidence, double score, ScanReport* report);
  // Whether this scan may change the map: not while lost, nor from a failed match, nor from a
  // poor one unless odometry confirms it (with loop closure), but a scan of unmapped space only
  // that odometry placed.
  bool MapMayChange(const ScanReport& report, bool odometry_predicted, const Pose2& guess) const;
  // The pose lies within loop_closure_odometry_confirms_distance/_angle of odometry's prediction.
  bool OdometryConfirms(const Pose2& prediction) const;
  // After every used scan: the motion for the next prediction, the horizon's clock, a pose that
  // is not finite replaced by the last good one, the report's state.
  // Lost for loop_closure_restart_after_lost_scans with loop closure on: the next scan starts a
  // new submap at its predicted pose.
  bool ShouldStartOver() const;
  // Loop closure is on and loop_closure_restart_after_lost_scans is not 0.
  bool CanStartOver() const;
  // Whether `motion` (between two scans) translates the robot: more than standing or turning on
  // the spot.
  bool Translates(const Pose2& motion) const;
  void StartOver(ScanReport* report);
  // `odometry_predicted`: odometry carried the pose to this scan (ShouldStartOver).
  void FinishScan(const Pose2& previous, double stamp, bool odometry_predicted, ScanReport* report);

  SlamOptions options_;
  std::unique_ptr<MapPyramid<HexLattice>> hex_maps_;
  std::unique_ptr<MapPyramid<SquareLattice>> square_maps_;
  HexScanMatcher hex_matcher_;
  SquareScanMatcher square_matcher_;
  std::shared_ptr<mapping::LatestSolution> solutions_;
  // Exactly one of these exists when loop closure is enabled with update_map, by lattice.
  std::unique_ptr<mapping::LoopClosure<HexLattice>> hex_loop_closure_;
  std::unique_ptr<mapping::LoopClosure<SquareLattice>> square_loop_closure_;
  bool loaded_map_ = false;

  Pose2 start_pose_;
  Pose2 pose_;
  Pose2 last_map_update_pose_;
  // A scan ProcessScan decided to insert but deferred: its mount, stamp and pose (the pose it
  // must still be at); its points are InsertedPoints() until the next scan.
  struct DeferredInsertion {
    SensorMount mount;
    double stamp = 0.0;
    Pose2 pose;
  };
  std::optional<DeferredInsertion> deferred_;
  std::optional<Pose2> last_odometry_;
  Pose2 last_motion_;  // the previous scan's estimated motion, for constant-velocity prediction
  // The motion before the previous scan's recovery, when it recovered: its jump may have mended
  // the pose the scan before had wrong, and then it is no velocity (AlternativePredictions).
  std::optional<Pose2> motion_before_recovery_;
  double scan_interval_average_ = 0.0;  // s, running average of the intervals between scans
  int scan_periods_ = 1;  // since the previous scan: more than one when scans went missing
  double average_score_ = 0.0;  // running average of accepted matches' mean occupancy
  double last_known_fraction_ = 0.0;  // the last judged match's share of endpoints on known cells
  int recoveries_ = 0;
  int odometry_faults_ = 0;
  std::optional<double> last_stamp_;
  bool map_initialized_ = false;
  int scans_processed_ = 0;
  int map_updates_ = 0;

  TrackingMonitor tracking_;
  Pose2 last_good_pose_;  // the last pose a scan placed while not lost: finite
  std::optional<double> last_match_stamp_;  // of the last scan whose match placed the robot
  bool previous_scan_matched_ = false;
  // The previous scan's match was judged failed while the state was not lost: without odometry
  // the constant-velocity prediction carries on over it (PredictsMotion).
  bool previous_match_failed_ = false;
  int lost_searches_ = 0;  // searches while lost so far: the next heading sector
  int times_lost_ = 0;
  int lost_scans_ = 0;          // lost scans the robot moved on (FinishScan, ShouldStartOver)
  double turned_while_lost_ = 0.0;  // rad the pose turned through while lost with odometry
  int restarts_ = 0;  // (Reset zeroes it: a first scan with restarts behind it starts over)
  int relocalizations_ = 0;
  // The whole-map search, built on the loaded map when first needed.
  std::unique_ptr<mapping::GlobalLocalizer> global_localizer_;
  // A loaded map whose pose (set, or the origin) is not confirmed yet: by good matches and by a
  // whole-map search that found no better place (global_checked_).
  bool pose_unconfirmed_ = false;
  bool global_checked_ = false;
  // Counts the pose's jumps that no motion explains (a given pose, a relocalization). A search
  // started before one carries its result over the front end's motion since its scan, which
  // then includes the jump: its result is dropped.
  int pose_jumps_ = 0;
  int global_search_jumps_ = 0;  // pose_jumps_ when the running search started

  ScanSanitizer sanitizer_;
  // Scratch reused across scans.
  std::vector<Eigen::Vector2d> sensor_points_;
  std::vector<Eigen::Vector2d> base_points_;    // the endpoints matched (base frame)
  std::vector<Eigen::Vector2d> insert_points_;  // every endpoint, when some are not matched
  std::vector<bool> grazing_;                   // per sensor point (MarkGrazingEndpoints)
  std::vector<Eigen::Vector2d> world_points_;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_SLAM_H_
