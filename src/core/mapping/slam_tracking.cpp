// Slam's tracking state: how each match is judged, what a failed or blind scan does to the pose,
// the search while lost, and the guard that keeps a non-finite pose out of the map and the
// reports. The rest of Slam is in slam.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/mapping/slam.h"
#include "mapping/slam_internal.h"

namespace hex_slam {
namespace {

using internal::AppendMessage;

// Matches are scored on this pyramid level (or the coarsest, if fewer): cells twice the finest,
// so an endpoint one finest cell off its wall still lands on it.
constexpr int kScoreLevel = 1;
// A search window over the budget is split into up to this many heading sectors: pi / 64 (about
// 3°) on each side of a sector's centre is as narrow as the normal recovery search's step.
constexpr int kMaxLostSearchSectors = 64;
// A translation under this fraction of the finest cell between two scans is standing still or
// turning on the spot: the odometry of a robot at rest, not a way out of its submap.
constexpr double kStillFractionOfCell = 0.1;
// The longest gap in the scans (in scan periods) read as scans that went missing while the
// robot drove on; a longer one is predicted as one period, and the prediction window and the
// recovery search take it from there.
constexpr int kMaxPredictedPeriods = 10;

// `motion` over `periods` scan periods, per period (small motions: the twist divided).
Pose2 PerPeriod(const Pose2& motion, int periods) {
  return Pose2(motion.x / periods, motion.y / periods, motion.theta / periods);
}

std::string Score(double score) {
  char text[16];
  std::snprintf(text, sizeof text, "%.2f", score);
  return text;
}

}  // namespace

bool Slam::PredictsMotion(double stamp) const {
  if (!options_.predict_constant_velocity) return false;
  // A failed match is no sign that the robot stopped (it drove into clutter, people, a room the
  // map has not seen: ACES without odometry failed five scans in a row at 0.1 m a scan, the pose
  // held, and the robot was lost for 1900 scans); a blind scan may be (a robot that goes blind
  // and stops must not be pushed on). So the prediction carries on over failed matches until the
  // state is lost, over blind scans only constant_velocity_horizon after the last match.
  return previous_scan_matched_ || previous_match_failed_ ||
         (last_match_stamp_ && stamp - *last_match_stamp_ <= options_.constant_velocity_horizon);
}

Pose2 Slam::NoOdometryPrediction(double stamp) const {
  return PredictsMotion(stamp) ? pose_ * last_motion_ : pose_;
}

std::vector<Pose2> Slam::AlternativePredictions(double stamp) const {
  std::vector<Pose2> guesses;
  if (!PredictsMotion(stamp)) return guesses;
  if (motion_before_recovery_) guesses.push_back(pose_ * *motion_before_recovery_);
  if (scan_periods_ > 1) {
    Pose2 guess = pose_;
    for (int i = 0; i < scan_periods_; ++i) guess = guess * last_motion_;
    guesses.push_back(guess);
  }
  return guesses;
}

int Slam::ScanPeriods(double interval) const {
  if (!(scan_interval_average_ > 0.0) || !(interval > 0.0)) return 1;
  const double periods = std::round(interval / scan_interval_average_);
  return periods >= 1.0 && periods <= kMaxPredictedPeriods ? static_cast<int>(periods) : 1;
}

MatchScore Slam::ScoreAt(const Pose2& pose) const {
  // With loop closure: the active submap, in the front end's frame as the pose is.
  return OnMatchingMaps([&](const auto& maps) {
    const int level = std::min(kScoreLevel, maps.size() - 1);
    return ScoreMatch(maps.level(level), base_points_, pose, options_.tracking.min_known_fraction,
                      options_.min_valid_beams);
  });
}

double Slam::LostSearchAngularWindow(bool odometry_predicted) const {
  const TrackingOptions& o = options_.tracking;
  if (!odometry_predicted) return o.lost_search_angular_window;
  return std::min(o.lost_search_angular_window,
                  o.lost_search_odometry_angular_window +
                      o.lost_search_odometry_turn_fraction * turned_while_lost_);
}

CorrelativeResult Slam::SearchWhileLost(const Pose2& centre, bool odometry_predicted) {
  CorrelativeSearchOptions window = options_.recovery;
  window.linear_window = options_.tracking.lost_search_linear_window;
  window.max_candidates =
      std::min(window.max_candidates, options_.tracking.lost_search_max_candidates);
  const double full = LostSearchAngularWindow(odometry_predicted);
  CorrelativeResult result;
  Pose2 sector_centre = centre;
  for (int sectors = 1; sectors <= kMaxLostSearchSectors; sectors *= 2) {
    window.angular_window = full / sectors;
    const int sector = lost_searches_ % sectors;
    const double heading = centre.theta - full + (2 * sector + 1) * window.angular_window;
    sector_centre = Pose2(centre.x, centre.y, NormalizeAngle(heading));
    result = SearchAround(sector_centre, window);
    if (result.refused.empty()) break;
  }
  // Over the budget even in the narrowest sector: coarser steps, not a search refused (with
  // hector's settings a lost robot searched only when its scan happened not to reach far).
  if (!result.refused.empty()) {
    window.max_step_coarsening = internal::kMaxSearchStepCoarsening;
    result = SearchAround(sector_centre, window);
  }
  ++lost_searches_;
  return result;
}

MatchResult Slam::MatchWhileLost(const Pose2& guess, bool odometry_predicted, ScanReport* report) {
  MatchResult result = Match(guess);
  const MatchScore score = ScoreAt(result.pose);
  if (MatchEvidence(options_.tracking, score, IsFinite(result.pose), options_.update_map) ==
      ScanEvidence::kGood) {
    return result;  // the robot is where it was thought to be (it was blind, or given a pose)
  }
  // Odometry carried the robot past the mapped part: nothing on the map contradicts it, and
  // a search would only find the place that puts the scan back on mapped cells (in a corridor,
  // the one turned by pi). The prediction stands, and once the robot has driven on it starts
  // over. (The single map never starts over, and a saved map cannot grow: both still search.)
  if (odometry_predicted && options_.update_map && CanStartOver() && !score.scored()) {
    return result;
  }
  if (std::optional<MatchResult> global = GlobalRelocalization(guess, result, report)) {
    return *global;
  }
  const CorrelativeResult search = SearchWhileLost(guess, odometry_predicted);
  if (!search.refused.empty()) {
    AppendMessage("the search while lost was refused: " + search.refused, &report->message);
    return result;
  }
  MatchResult found = Match(search.pose);
  const MatchScore found_score = ScoreAt(found.pose);
  const bool better = found_score.scored() &&
                      (!score.scored() || found_score.score > score.score);
  if (!IsFinite(found.pose) || !better) return result;
  report->relocalized = true;  // kept only if JudgeMatch takes the pose
  return found;
}

mapping::GlobalLocalizationStats Slam::global_localization_stats() const {
  return global_localizer_ ? global_localizer_->stats() : mapping::GlobalLocalizationStats();
}

void Slam::WaitForGlobalLocalization() {
  if (global_localizer_) global_localizer_->Wait();
}

bool Slam::CanCheckGlobally() const {
  return loaded_map_ && !options_.update_map && options_.global_localization.enabled;
}

std::optional<MatchResult> Slam::GlobalRelocalization(const Pose2& guess,
                                                      const MatchResult& current,
                                                      ScanReport* report) {
  if (!CanCheckGlobally()) return std::nullopt;
  if (!global_localizer_) {
    global_localizer_ = OnMatchingMaps([this](const auto& maps) {
      const int level = std::min(options_.global_localization.search_level, maps.size() - 1);
      return std::make_unique<mapping::GlobalLocalizer>(maps.level(level),
                                                        options_.global_localization);
    });
  }
  std::optional<mapping::GlobalSearchResult> done = global_localizer_->Poll();
  if (done && global_search_jumps_ != pose_jumps_) done.reset();  // see pose_jumps_
  if (!done && global_localizer_->Start(base_points_, guess)) {
    global_search_jumps_ = pose_jumps_;
    done = global_localizer_->Poll();
  }
  if (!done) return std::nullopt;
  // A search checks the pose when it finds nothing better: no place above its minimum score,
  // the same place, or a better one that is then taken. An ambiguous search, or a found place
  // the map does not back (the front end moved since the searched scan, and a wrong pose moves
  // by its corrections), is inconclusive: the next scan searches again.
  if (!done->match) {
    global_checked_ = true;
    return std::nullopt;
  }
  if (done->ambiguous()) {
    AppendMessage("the whole-map search found several places the scan fits: none taken",
                  &report->message);
    return std::nullopt;
  }
  // The searched scan's pose, moved on by the front end's motion since then.
  const Pose2 carried = done->match->pose * RelativePose(done->scan_pose, guess);
  const MatchResult found = Match(carried);
  const Pose2 apart = RelativePose(current.pose, found.pose);
  const mapping::GlobalLocalizationOptions& o = options_.global_localization;
  if (apart.translation().norm() <= o.matcher.peak_radius &&
      std::abs(apart.theta) <= o.matcher.peak_angle) {
    global_checked_ = true;
    return std::nullopt;  // the same place: the search agrees with the match
  }
  // Unambiguous means the current place, too, scored under ambiguity_ratio of the found one
  // over the whole map: no comparison of the two by the tracking score, which saturates on
  // clean scans and ignores endpoints on unknown cells (the ROSbot's rooms scored 1.0 at a
  // place 3.1 m off). It must still back the found one.
  if (!MapSupports(found)) return std::nullopt;
  global_checked_ = true;
  ++global_localizer_->stats().accepted;
  report->relocalized = report->relocalized_globally = true;
  return found;
}

void Slam::ConfirmLoadedPose(const Pose2& guess, ScanReport* report) {
  if (std::optional<MatchResult> global = GlobalRelocalization(guess, report->match, report)) {
    report->match = *global;
  }
}

void Slam::Track(ScanEvidence evidence, double score, ScanReport* report) {
  report->evidence = evidence;
  if (!tracking_.Update(evidence, score)) return;
  report->tracking_changed = true;
  if (tracking_.state() == TrackingState::kLost) {
    ++times_lost_;
    lost_searches_ = 0;
  }
}

void Slam::JudgeMatch(const Pose2& guess, bool odometry_predicted, ScanReport* report) {
  const MatchResult& match = report->match;
  report->score = ScoreAt(match.pose);
  last_known_fraction_ = report->score.known_fraction();
  const bool was_lost = tracking_.state() == TrackingState::kLost;
  const ScanEvidence evidence =
      MatchEvidence(options_.tracking, report->score, IsFinite(match.pose), options_.update_map);
  // On a loaded map a wrong place can fit the scan as well as the right one (the ROSbot's rooms
  // scored 1.0 3.1 m off): good matches make the state ok only once a whole-map search has
  // checked the pose.
  const bool awaiting_check = pose_unconfirmed_ && CanCheckGlobally() && !global_checked_;
  Track(evidence == ScanEvidence::kGood && awaiting_check ? ScanEvidence::kUnconfirmed : evidence,
        report->score.score, report);
  // A match that contradicts the map is likelier wrong than the prediction, and while lost only
  // a match the map agrees with may move the robot.
  const bool use = evidence == ScanEvidence::kGood || (evidence == ScanEvidence::kPoor && !was_lost);
  report->relocalized = report->relocalized && use;
  report->relocalized_globally = report->relocalized_globally && use;
  if (report->relocalized) ++relocalizations_;
  // Too little of the scan on the map to judge it (a slow laser, a fast robot, into unmapped
  // space between two scans): the match had nothing to pull on, and odometry's pose stands. The
  // scan is mapped there, as hector maps every scan, or the map would never reach the robot.
  if (odometry_predicted && options_.update_map && !report->score.scored() &&
      std::isnan(report->score.known_agreement) && !was_lost) {
    pose_ = guess;
    report->placed_by_odometry = true;
    AppendMessage("too little of the scan on the map to match: odometry's pose kept",
                  &report->message);
    return;
  }
  if (!use) {
    pose_ = guess;
    if (evidence == ScanEvidence::kFailed) {
      AppendMessage(report->score.scored()
                        ? "the match failed (score " + Score(report->score.score) +
                              ", below tracking_lost_score): the prediction is kept"
                        : "the match failed (most endpoints off the map): the prediction is kept",
                    &report->message);
    }
    return;
  }
  pose_ = match.pose;
  report->pose_from_scan = true;
  report->covariance = MatchCovariance(match, base_points_);
}

bool Slam::MapMayChange(const ScanReport& report, bool odometry_predicted,
                        const Pose2& guess) const {
  if (!IsFinite(pose_) || tracking_.state() == TrackingState::kLost) return false;
  if (report.placed_by_odometry) return true;
  if (!report.pose_from_scan) return false;
  // A scan of mostly unmapped space (exploring) goes in when its part on the map agrees.
  const double agreement =
      report.score.scored() ? report.score.score : report.score.known_agreement;
  if (agreement >= options_.tracking.ok_score) return true;
  return odometry_predicted && report.evidence == ScanEvidence::kPoor && loop_closure_active() &&
         OdometryConfirms(guess);
}

bool Slam::OdometryConfirms(const Pose2& prediction) const {
  const mapping::LoopClosureOptions& o = options_.loop_closure;
  const Pose2 off = RelativePose(prediction, pose_);
  return o.odometry_confirms_distance > 0.0 &&
         off.translation().norm() <= o.odometry_confirms_distance &&
         std::abs(off.theta) <= o.odometry_confirms_angle;
}

void Slam::FinishScan(const Pose2& previous, double stamp, bool odometry_predicted,
                      ScanReport* report) {
  if (report->outcome == ScanOutcome::kInitialized && restarts_ > 0) {
    tracking_.StartOver("lost for " +
                        std::to_string(options_.loop_closure.restart_after_lost_scans) +
                        " scans: started over on a new submap at the predicted pose; loop "
                        "closure places it");
    report->tracking_changed = true;
    report->pose_from_scan = false;
    report->evidence = ScanEvidence::kPoor;
  } else if (report->outcome == ScanOutcome::kInitialized) {
    tracking_.Reset();  // the first scan defines the map and the pose on it
    report->pose_from_scan = true;
    report->evidence = ScanEvidence::kGood;
  }
  if (!IsFinite(pose_)) {
    pose_ = last_good_pose_;
    report->pose_from_scan = false;
    AppendMessage("the estimate was not finite: back to the last good pose", &report->message);
    if (tracking_.Lose("the estimate was not finite")) {
      report->tracking_changed = true;
      ++times_lost_;
      lost_searches_ = 0;
    }
  }
  const bool lost = tracking_.state() == TrackingState::kLost;
  // While lost the pose holds (or follows odometry), and a relocalization's jump is no velocity.
  const Pose2 motion_before = last_motion_;
  // Over several scan periods (scans went missing) the motion is that many periods' worth.
  last_motion_ = lost || report->relocalized
                     ? Pose2()
                     : PerPeriod(RelativePose(previous, pose_), scan_periods_);
  motion_before_recovery_.reset();
  if (report->recovered && !lost && !report->relocalized) motion_before_recovery_ = motion_before;
  if (report->relocalized) ++pose_jumps_;
  if (report->pose_from_scan) last_match_stamp_ = stamp;
  previous_scan_matched_ = report->pose_from_scan;
  previous_match_failed_ = report->evidence == ScanEvidence::kFailed && !lost;
  if (report->pose_from_scan && !lost) last_good_pose_ = pose_;
  if (tracking_.state() == TrackingState::kOk && (global_checked_ || !CanCheckGlobally())) {
    pose_unconfirmed_ = false;
  }
  if (!report->pose_from_scan || lost || !report->covariance.allFinite()) {
    report->covariance = UnknownPoseCovariance();
  }
  // Counted: lost scans matched (and no place found) with odometry carrying the pose, so that a
  // new submap starts where the robot is once it has left the active submap's reach. Without
  // odometry the lost pose holds while the robot moves on: a submap started there would be
  // drawn where the robot is not (on ACES without odometry the front end then ran away, 11 m a
  // scan). A blind scan says nothing, and nor does one taken standing or turning on the spot:
  // the robot is still where its submap is and can find itself on it again (ACES stood lost at
  // its roundabout for 50 scans and relocalized as it turned; started over there, the near-empty
  // new submap let that turn slip 0.2 rad, which no local search window covered).
  if (!lost) {
    lost_scans_ = 0;
    turned_while_lost_ = 0.0;
  } else if (odometry_predicted) {
    const Pose2 motion = RelativePose(previous, pose_);
    turned_while_lost_ += std::abs(motion.theta);
    if (report->outcome == ScanOutcome::kMatched && Translates(motion)) ++lost_scans_;
  }
  if (ShouldStartOver()) StartOver(report);
  report->pose = pose_;
  report->tracking_state = tracking_.state();
  report->tracking_reason = tracking_.reason();
}

bool Slam::Translates(const Pose2& motion) const {
  return motion.translation().norm() > kStillFractionOfCell * options_.map_resolution;
}

bool Slam::CanStartOver() const {
  return options_.loop_closure.restart_after_lost_scans > 0 && loop_closure_active();
}

bool Slam::ShouldStartOver() const {
  return CanStartOver() && lost_scans_ >= options_.loop_closure.restart_after_lost_scans;
}

void Slam::StartOver(ScanReport* report) {
  // The old submaps keep what was mapped before the loss; none of them is written again.
  if (hex_loop_closure_) hex_loop_closure_->FinishActiveSubmaps();
  if (square_loop_closure_) square_loop_closure_->FinishActiveSubmaps();
  map_initialized_ = false;
  lost_scans_ = 0;
  ++restarts_;
  AppendMessage("lost for " + std::to_string(options_.loop_closure.restart_after_lost_scans) +
                    " scans: the next scan starts a new submap",
                &report->message);
}

}  // namespace hex_slam
