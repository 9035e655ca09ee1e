#include "hex_slam/mapping/slam.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/sensor/grazing_endpoints.h"
#include "mapping/slam_internal.h"

namespace hex_slam {
namespace {

using internal::AppendMessage;

// Weight of the newest score in the running average that the recovery trigger compares with.
constexpr double kScoreAverageWeight = 0.1;
// Weight of the newest interval in the running average of the intervals between scans.
constexpr double kScanIntervalAverageWeight = 0.1;
// A laser measures its scans about a period apart: an interval under this fraction of the
// average is the stamp of when the scan was taken in, not of when it was measured.
constexpr double kBunchedIntervalFraction = 0.25;
// A collapsed match yields to the wide search's pose only when that pose puts more than this
// many times as many endpoints on occupied cells: a few agreeing endpoints on a young map are
// not enough to move the robot by a whole turn.
constexpr int kCollapsedRetryAgreementGain = 2;
// A submap started beside an older one reserves the older's box and its first scan's grown by
// this fraction of reserve_radius (3 m at the defaults). Intel, margins of 3, 6 and 9 m: peak RSS
// 293, 306 and 325 MB (340 with reserve_radius around the first scan alone), about as many
// growths (0-2 per submap), the same results.
constexpr double kOverlapReserveFraction = 1.0 / 6.0;

// Exactly the same pose (a NaN is never the same).
bool SamePose(const Pose2& a, const Pose2& b) {
  return a.x == b.x && a.y == b.y && a.theta == b.theta;
}

SlamOptions Validated(const SlamOptions& options) {
  const std::vector<std::string> errors = options.Validate();
  if (!errors.empty()) {
    std::ostringstream s;
    s << "invalid SLAM options:";
    for (const std::string& e : errors) s << "\n  " << e;
    throw std::invalid_argument(s.str());
  }
  return options;
}

// `covariance` (x, y, theta) seen from a frame whose axes are turned by `angle` from its own.
Eigen::Matrix3d RotatedCovariance(const Eigen::Matrix3d& covariance, double angle) {
  if (angle == 0.0) return covariance;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() = Eigen::Rotation2Dd(angle).toRotationMatrix();
  return rotation * covariance * rotation.transpose();
}

template <class Lattice>
std::string MapOutOfReach(const GridMap<Lattice>& finest, const SlamOptions& o,
                          const Eigen::Vector2d& position) {
  const Eigen::AlignedBox2d known = finest.KnownExtent();
  if (!known.isEmpty()) {
    const double distance = known.exteriorDistance(position);
    if (distance > o.laser_max_dist) {
      std::ostringstream s;
      s << "(" << position.x() << ", " << position.y() << ") lies " << distance
        << " m from the nearest cell the map knows, farther than laser_max_dist ("
        << o.laser_max_dist << " m): scans there could not see the map";
      return s.str();
    }
  }
  if (!o.update_map || !o.map_auto_grow) return "";
  const Eigen::Vector2d reach = Eigen::Vector2d::Constant(o.laser_max_dist);
  GridIndex lo, hi;
  finest.lattice().IndexBounds(Eigen::AlignedBox2d(position - reach, position + reach), &lo, &hi);
  const GridRect needed = finest.rect().Union(GridRect::FromCorners(lo, hi));
  if (static_cast<double>(needed.width) * needed.height > static_cast<double>(o.map_max_cells)) {
    std::ostringstream s;
    s << "(" << position.x() << ", " << position.y() << ") is out of the map's reach: holding "
      << "scans there takes " << static_cast<double>(needed.width) * needed.height
      << " cells per level, more than map_max_cells (" << o.map_max_cells << ")";
    return s.str();
  }
  return "";
}

}  // namespace

const char* ScanOutcomeName(ScanOutcome outcome) {
  switch (outcome) {
    case ScanOutcome::kMatched: return "matched";
    case ScanOutcome::kInitialized: return "initialized";
    case ScanOutcome::kKnownPose: return "known pose";
    case ScanOutcome::kInvalidScan: return "invalid scan";
    case ScanOutcome::kTooFewPoints: return "too few points";
    case ScanOutcome::kTimeWentBackwards: return "time went backwards";
  }
  return "unknown";
}

Slam::Slam(const SlamOptions& options)
    : options_(Validated(options)),
      hex_matcher_(options_.matcher),
      square_matcher_(options_.matcher),
      solutions_(std::make_shared<mapping::LatestSolution>()),
      tracking_(options_.tracking) {
  const OccupancyModel model = MapOccupancyModel(options_);
  if (options_.lattice == "hex") {
    hex_maps_ = std::make_unique<MapPyramid<HexLattice>>(
        options_.map_resolution, EffectiveLevels(options_), model, MapGrowthPolicy(options_),
        InitialMapExtent(options_));
  } else {
    square_maps_ = std::make_unique<MapPyramid<SquareLattice>>(
        options_.map_resolution, EffectiveLevels(options_), model, MapGrowthPolicy(options_),
        InitialMapExtent(options_));
  }
  StartLoopClosure();
}

Slam::~Slam() = default;

void Slam::StartLoopClosure() {
  // The old worker (if any) stops before the new one starts.
  hex_loop_closure_.reset();
  square_loop_closure_.reset();
  loaded_map_ = false;
  if (!options_.loop_closure.enabled || !options_.update_map) return;
  mapping::SubmapGridParameters grid;
  grid.finest_spacing = options_.map_resolution;
  grid.levels = EffectiveLevels(options_);
  grid.model = MapOccupancyModel(options_);
  grid.growth = MapGrowthPolicy(options_);
  // Submaps' storage is sized to what they will hold (below), so it is made resident when
  // allocated (Paging). Intel subset offline with odometry, four interleaved pairs: 1.15-1.29x
  // faster, scan path p99 1.27-1.65 -> 0.87-1.05 ms, peak RSS 203 -> 220 MB; without odometry
  // (matching dominates) 0.97-1.08x; the trajectories byte-identical.
  grid.growth.prefault = true;
  // While the newer submap fills, the robot moves at least map_update_distance_thresh per
  // inserted scan (about that much, driving; the older submap's second half is the newer one's
  // first). Not the laser's range too: the reserved but unwritten width of every row makes the
  // written cells spread over more pages (first touches), which costs more than growing.
  grid.reserve_radius =
      options_.loop_closure.submaps.num_scans * options_.map_update_distance_thresh;
  grid.overlap_reserve_margin = kOverlapReserveFraction * grid.reserve_radius;
  if (hex_maps_) {
    hex_loop_closure_ = std::make_unique<mapping::LoopClosure<HexLattice>>(
        options_.loop_closure, options_.matcher, grid, solutions_);
  } else {
    square_loop_closure_ = std::make_unique<mapping::LoopClosure<SquareLattice>>(
        options_.loop_closure, options_.matcher, grid, solutions_);
  }
}

bool Slam::loop_closure_active() const {
  return (hex_loop_closure_ || square_loop_closure_) && !loaded_map_;
}

Pose2 Slam::GlobalPose() const {
  return loop_closure_active() ? solutions_->Get()->correction * pose_ : pose_;
}

std::vector<std::shared_ptr<const mapping::TrajectoryNode>> Slam::Nodes() const {
  if (hex_loop_closure_) return hex_loop_closure_->nodes();
  if (square_loop_closure_) return square_loop_closure_->nodes();
  return {};
}

mapping::LoopClosureStats Slam::loop_closure_stats() const {
  if (hex_loop_closure_) return hex_loop_closure_->stats();
  if (square_loop_closure_) return square_loop_closure_->stats();
  return mapping::LoopClosureStats();
}

void Slam::FinishLoopClosure() {
  if (!loop_closure_active()) return;
  if (hex_loop_closure_) hex_loop_closure_->FinishTrajectory();
  if (square_loop_closure_) square_loop_closure_->FinishTrajectory();
}

void Slam::FinishTrajectory() {
  FinishLoopClosure();
  RefreshGlobalMap();
}

void Slam::RefreshGlobalMap() {
  if (!loop_closure_active()) return;
  const std::shared_ptr<const mapping::PoseGraphSolution> solution = solutions_->Get();
  if (hex_loop_closure_) DrawGlobalMap(hex_loop_closure_->nodes(), *solution, hex_maps_.get());
  if (square_loop_closure_) {
    DrawGlobalMap(square_loop_closure_->nodes(), *solution, square_maps_.get());
  }
}

const MapPyramid<HexLattice>& Slam::HexMatchingMaps() const {
  const MapPyramid<HexLattice>* submap =
      loop_closure_active() ? hex_loop_closure_->matching_maps() : nullptr;
  return submap ? *submap : *hex_maps_;
}

const MapPyramid<SquareLattice>& Slam::SquareMatchingMaps() const {
  const MapPyramid<SquareLattice>* submap =
      loop_closure_active() ? square_loop_closure_->matching_maps() : nullptr;
  return submap ? *submap : *square_maps_;
}

std::size_t Slam::MemoryBytes() const {
  std::size_t bytes = hex_maps_ ? hex_maps_->MemoryBytes() : square_maps_->MemoryBytes();
  if (hex_loop_closure_) bytes += hex_loop_closure_->MemoryBytes();
  if (square_loop_closure_) bytes += square_loop_closure_->MemoryBytes();
  return bytes;
}

void Slam::Reset(const Pose2& pose) {
  deferred_.reset();
  if (hex_maps_) hex_maps_->Clear();
  if (square_maps_) square_maps_->Clear();
  if (hex_loop_closure_ || square_loop_closure_) {
    StartLoopClosure();
    solutions_->Publish(mapping::PoseGraphSolution());
  }
  start_pose_ = pose_ = last_map_update_pose_ = pose;
  last_odometry_.reset();
  last_motion_ = Pose2();
  motion_before_recovery_.reset();
  scan_interval_average_ = 0.0;
  scan_periods_ = 1;
  last_stamp_.reset();
  map_initialized_ = false;
  average_score_ = 0.0;
  last_known_fraction_ = 0.0;
  recoveries_ = 0;
  odometry_faults_ = 0;
  scans_processed_ = 0;
  map_updates_ = 0;
  tracking_.Reset();
  last_good_pose_ = pose;
  last_match_stamp_.reset();
  previous_scan_matched_ = previous_match_failed_ = false;
  lost_searches_ = times_lost_ = relocalizations_ = 0;
  lost_scans_ = restarts_ = 0;
  turned_while_lost_ = 0.0;
  global_localizer_.reset();
  pose_unconfirmed_ = global_checked_ = false;
}

void Slam::UseLoadedMap() {
  deferred_.reset();
  loaded_map_ = true;
  map_initialized_ = true;
  last_map_update_pose_ = pose_;
  average_score_ = 0.0;
  tracking_.Update(ScanEvidence::kUnconfirmed, std::nan(""));
  global_localizer_.reset();  // its grids are the previous map's
  pose_unconfirmed_ = true;
  global_checked_ = false;
}

std::string Slam::OutOfReach(const Pose2& pose) const {
  if (!IsFinite(pose)) return "the pose is not finite";
  return hex_maps_ ? MapOutOfReach(hex_maps_->level(0), options_, pose.translation())
                   : MapOutOfReach(square_maps_->level(0), options_, pose.translation());
}

bool Slam::SetPose(const Pose2& pose) {
  if (!OutOfReach(pose).empty()) return false;
  // `pose` is in the map frame; with loop closure the front end's frame is the correction off it.
  pose_ = loop_closure_active() ? solutions_->Get()->correction.inverse() * pose : pose;
  if (!map_initialized_) start_pose_ = pose_;
  ++pose_jumps_;
  deferred_.reset();  // (even to the same pose: the caller moved the robot since that scan)
  if (loaded_map_) {
    // A pose given from outside is unconfirmed on the map, as the one it was loaded with.
    pose_unconfirmed_ = true;
    global_checked_ = false;
    tracking_.Update(ScanEvidence::kUnconfirmed, std::nan(""));
  }
  return true;
}

bool Slam::ShouldUpdateMap() const {
  if (!options_.update_map) return false;
  const Pose2 moved = RelativePose(last_map_update_pose_, pose_);
  return moved.translation().norm() > options_.map_update_distance_thresh ||
         std::abs(moved.theta) > options_.map_update_angle_thresh;
}

bool Slam::MapGoingStale(const ScanReport& report) const {
  if (!options_.update_map || options_.map_update_score_margin <= 0.0 || !report.score.scored()) {
    return false;
  }
  return report.score.score < options_.tracking.ok_score + options_.map_update_score_margin &&
         (pose_.translation() - last_map_update_pose_.translation()).norm() >
             options_.map_update_min_distance;
}

int Slam::InsertIntoMap(const SensorMount& mount, double stamp, Eigen::AlignedBox2d* region) {
  last_map_update_pose_ = pose_;
  map_initialized_ = true;
  ++map_updates_;
  *region = Eigen::AlignedBox2d();
  int node = -1;
  if (loop_closure_active()) {
    const Eigen::Vector2d sensor_origin = mount.origin();
    node = hex_loop_closure_
               ? hex_loop_closure_->InsertScan(stamp, pose_, sensor_origin, InsertedPoints())
               : square_loop_closure_->InsertScan(stamp, pose_, sensor_origin, InsertedPoints());
    if (!options_.loop_closure.live_map) return node;
  }
  // The single map, or the live global map at the scan's pose in the map frame.
  const Pose2 pose = node >= 0 ? GlobalPose() : pose_;
  const Eigen::Vector2d origin = pose * mount.origin();
  region->extend(origin);
  world_points_.clear();
  const PointTransform to_world(pose);
  for (const Eigen::Vector2d& p : InsertedPoints()) {
    world_points_.push_back(to_world(p));
    region->extend(world_points_.back());
  }
  if (hex_maps_) hex_maps_->InsertScan(origin, world_points_);
  if (square_maps_) square_maps_->InsertScan(origin, world_points_);
  return node;
}

MatchResult Slam::Match(const Pose2& guess, GuessSource source) const {
  return hex_maps_ ? hex_matcher_.Match(HexMatchingMaps(), base_points_, guess, source)
                   : square_matcher_.Match(SquareMatchingMaps(), base_points_, guess, source);
}

CorrelativeResult Slam::SearchAround(const Pose2& centre,
                                     const CorrelativeSearchOptions& window) const {
  return OnMatchingMaps([&](const auto& maps) {
    return SearchCorrelative(maps.level(maps.size() - 1), base_points_, centre, window);
  });
}

bool Slam::MapSupports(const MatchResult& retry) const {
  // mean_occupancy takes unknown cells as half occupied, so a search can raise it by moving the
  // scan off the map, where nothing contradicts it: a retry must convince the tracking score.
  return MatchEvidence(options_.tracking, ScoreAt(retry.pose), IsFinite(retry.pose),
                       options_.update_map) == ScanEvidence::kGood;
}

bool Slam::CollapsedMatchYields(const MatchResult& match, const MatchResult& retry) const {
  if (!(options_.recovery_wide_collapse_ratio > 0.0)) return false;
  const MatchScore now = ScoreAt(match.pose);
  if (now.scored() || now.points == 0) return false;
  if (!(now.known_fraction() < options_.recovery_wide_collapse_ratio * last_known_fraction_)) {
    return false;
  }
  // Within the first window, Gauss–Newton and the first search already had their say.
  const bool beyond_first_window =
      std::abs(NormalizeAngle(retry.pose.theta - match.pose.theta)) >
          options_.recovery.angular_window ||
      (retry.pose.translation() - match.pose.translation()).cwiseAbs().maxCoeff() >
          options_.recovery.linear_window;
  if (!beyond_first_window) return false;
  const MatchScore there = ScoreAt(retry.pose);
  return there.known_agreement >= options_.tracking.ok_score &&
         there.agreeing > kCollapsedRetryAgreementGain * now.agreeing;
}

double Slam::SearchScore(const Pose2& pose) const {
  return OnMatchingMaps([&](const auto& maps) {
    return CorrelativeScore(maps.level(maps.size() - 1), base_points_, pose, options_.recovery);
  });
}

double Slam::RecoveryStep() const {
  return OnMatchingMaps([&](const auto& maps) {
    return options_.recovery.step_cells * maps.level(maps.size() - 1).lattice().spacing();
  });
}

std::optional<CorrelativeSearchOptions> Slam::PredictionWindow(double mean_range) const {
  if (!last_match_stamp_) return std::nullopt;
  // A scan stamped far sooner after the last match than scans come (a logger that stamps what
  // it takes in at once: a third of the Intel log's intervals are under 20 ms, at 0.2 s on
  // average) was still measured about a period later, and a turn speeding up over it went
  // unpredicted and unsearched. Only such stamps are doubted: raising every interval short of
  // the average to it (stamps' jitter included) cost ACES without odometry its track.
  double dt = *last_stamp_ - *last_match_stamp_;
  if (dt < kBunchedIntervalFraction * scan_interval_average_) dt = scan_interval_average_;
  CorrelativeSearchOptions window = options_.recovery;
  window.linear_window =
      std::min(options_.prediction_acc_lim_x * dt * dt, options_.recovery.linear_window);
  window.angular_window =
      std::min(options_.prediction_acc_lim_theta * dt * dt, options_.recovery.angular_window);
  const double reach = window.linear_window + window.angular_window * mean_range;
  if (!(reach > RecoveryStep())) return std::nullopt;
  return window;
}

void Slam::SearchPredictionWindow(const Pose2& guess, const CorrelativeSearchOptions& window,
                                  double mean_range, MatchResult* result, bool* recovered,
                                  std::string* message) const {
  const CorrelativeResult search = SearchAround(guess, window);
  if (!search.refused.empty()) {
    AppendMessage("prediction search refused: " + search.refused, message);
    return;
  }
  // Gauss–Newton from the prediction already reached the search's best.
  if (EndpointMoveBound(search.pose, result->pose, mean_range) <= RecoveryStep()) return;
  const MatchResult retry = Match(search.pose);
  if (SearchScore(retry.pose) > SearchScore(result->pose) && MapSupports(retry)) {
    *result = retry;
    *recovered = true;
  }
}

void Slam::UpdateScanInterval(double stamp) {
  const double interval = last_stamp_ ? stamp - *last_stamp_ : 0.0;
  scan_periods_ = ScanPeriods(interval);
  if (!(interval > 0.0)) return;
  scan_interval_average_ = scan_interval_average_ > 0.0
                               ? (1.0 - kScanIntervalAverageWeight) * scan_interval_average_ +
                                     kScanIntervalAverageWeight * interval
                               : interval;
}

void Slam::MatchAlternativePredictions(MatchResult* result, bool* recovered) const {
  for (const Pose2& guess : AlternativePredictions(*last_stamp_)) {
    const MatchResult other = Match(guess);
    if (!(other.cost < result->cost)) continue;
    *result = other;
    // A prediction won, not a search: the scan was tracked, and its motion is velocity.
    *recovered = false;
  }
}

MatchResult Slam::MatchWithRecovery(const Pose2& guess, bool predicted_by_odometry,
                                    bool* recovered, std::string* message) {
  *recovered = false;
  MatchResult result =
      Match(guess, predicted_by_odometry ? GuessSource::kOdometry : GuessSource::kPrediction);
  if (!predicted_by_odometry) {
    const double mean_range = MeanRange(base_points_);
    if (const auto window = PredictionWindow(mean_range)) {
      SearchPredictionWindow(guess, *window, mean_range, &result, recovered, message);
    }
    MatchAlternativePredictions(&result, recovered);
  }
  const auto collapsed = [this](const MatchResult& r) {
    return options_.recovery_score_ratio > 0.0 && average_score_ > 0.0 &&
           r.mean_occupancy < options_.recovery_score_ratio * average_score_;
  };
  // The window around the prediction, then (if the match is still collapsed) the wide one.
  CorrelativeSearchOptions wide = options_.recovery;
  wide.linear_window = options_.recovery_wide_linear_window;
  wide.angular_window = options_.recovery_wide_angular_window;
  wide.max_step_coarsening = internal::kMaxSearchStepCoarsening;
  const bool has_wide = wide.linear_window > 0.0 || wide.angular_window > 0.0;
  for (const CorrelativeSearchOptions* window : {&options_.recovery, &wide}) {
    if (!collapsed(result) || (window == &wide && !has_wide)) break;
    const CorrelativeResult search = SearchAround(guess, *window);
    if (!search.refused.empty()) {
      AppendMessage("recovery search refused: " + search.refused, message);
      break;
    }
    const MatchResult retry = Match(search.pose);
    const bool takes = (retry.mean_occupancy > result.mean_occupancy && MapSupports(retry)) ||
                       (window == &wide && !predicted_by_odometry &&
                        CollapsedMatchYields(result, retry));
    if (takes) {
      result = retry;
      *recovered = true;
    }
  }
  if (*recovered) ++recoveries_;
  average_score_ = average_score_ > 0.0 ? (1.0 - kScoreAverageWeight) * average_score_ +
                                              kScoreAverageWeight * result.mean_occupancy
                                        : result.mean_occupancy;
  return result;
}

void Slam::ToBasePoints(const SensorMount& mount, BeamCounts* beams) {
  base_points_.clear();
  insert_points_.clear();
  // Only a scan with grazing endpoints needs a second list (InsertedPoints).
  const bool any_grazing =
      MarkGrazingEndpoints(sensor_points_, options_.laser_match_max_incidence, &grazing_) > 0;
  for (std::size_t i = 0; i < sensor_points_.size(); ++i) {
    const Eigen::Vector2d& p = sensor_points_[i];
    const double height = mount.HeightOf(p);
    if (!(height > options_.laser_z_min_value && height < options_.laser_z_max_value)) {
      ++beams->outside_height;
      continue;
    }
    const Eigen::Vector2d base = mount.ToBase(p);
    if (any_grazing) insert_points_.push_back(base);
    if (grazing_[i]) {
      ++beams->grazing;
    } else {
      base_points_.push_back(base);
    }
  }
  beams->valid = static_cast<int>(InsertedPoints().size());
}

Pose2 Slam::PredictPose(const std::optional<Pose2>& odometry, ScanReport* report) {
  const Pose2 without_odometry = NoOdometryPrediction(*last_stamp_);  // this scan's stamp
  if (!odometry) return without_odometry;
  if (!IsFinite(*odometry)) {
    // Nothing to measure the next increment from either.
    last_odometry_.reset();
    report->odometry_fault = true;
    report->message = "odometry is not finite: not used, and the next is not compared with it";
    ++odometry_faults_;
    return without_odometry;
  }
  const std::optional<Pose2> previous = last_odometry_;
  last_odometry_ = odometry;  // re-anchored here even when the increment is dropped
  if (!previous) return pose_;  // the first odometry: nothing to measure motion from yet
  const Pose2 increment = RelativePose(*previous, *odometry);
  const double distance = increment.translation().norm();
  if (distance <= options_.odometry_jump_distance_thresh &&
      std::abs(increment.theta) <= options_.odometry_jump_angle_thresh) {
    return pose_ * increment;
  }
  std::ostringstream s;
  s << "odometry jumped " << distance << " m and " << increment.theta
    << " rad since the previous scan (odometry_jump_distance_thresh "
    << options_.odometry_jump_distance_thresh << " m, odometry_jump_angle_thresh "
    << options_.odometry_jump_angle_thresh << " rad): increment dropped";
  report->odometry_fault = true;
  report->message = s.str();
  ++odometry_faults_;
  return without_odometry;
}

bool Slam::InsertDeferredScan(ScanReport* report) {
  if (!deferred_) return false;
  const DeferredInsertion deferred = *deferred_;
  deferred_.reset();
  // Not where it was matched (FinishScan took a non-finite estimate back to the last good pose,
  // or the pose was set since): it must not go in where it was not seen.
  if (!SamePose(pose_, deferred.pose)) return false;
  report->node_id = InsertIntoMap(deferred.mount, deferred.stamp, &report->updated_region);
  report->map_updated = true;
  report->map_update_deferred = false;
  // The pose is out and the next scan not in: the time to complete a submap it will match.
  if (hex_loop_closure_) hex_loop_closure_->CompleteMatchingSubmap();
  if (square_loop_closure_) square_loop_closure_->CompleteMatchingSubmap();
  return true;
}

ScanReport Slam::ProcessScan(const LaserScan& scan, const SensorMount& mount,
                             const std::optional<Pose2>& odometry, bool defer_map_update) {
  if (deferred_) {
    // The caller did not insert the last scan: in it goes now, before its points are replaced.
    ScanReport previous;
    InsertDeferredScan(&previous);
  }
  ScanReport report;
  report.pose = pose_;
  report.global_pose = GlobalPose();
  if (!std::isfinite(scan.stamp)) {
    report.outcome = ScanOutcome::kInvalidScan;
    report.message = "the scan's stamp is not finite";
    return report;
  }
  const std::string bad_mount = CheckSensorPose(mount.PlanarPose(), "sensor pose");
  if (!bad_mount.empty()) {
    report.outcome = ScanOutcome::kInvalidScan;
    report.message = bad_mount;
    return report;
  }
  if (last_stamp_ && scan.stamp < *last_stamp_) {
    report.outcome = ScanOutcome::kTimeWentBackwards;
    std::ostringstream s;
    s << "scan stamped " << scan.stamp << " s, before the previous one at " << *last_stamp_
      << " s";
    report.message = s.str();
    return report;
  }
  const RangeFilter filter{options_.laser_min_dist, options_.laser_max_dist,
                           options_.laser_range_max_is_no_return, options_.laser_range_max_margin};
  const ScanError error =
      sanitizer_.Sanitize(scan, filter, &sensor_points_, &report.beams, &report.message);
  if (error != ScanError::kNone) {
    report.outcome = ScanOutcome::kInvalidScan;
    return report;
  }
  UpdateScanInterval(scan.stamp);
  last_stamp_ = scan.stamp;
  ++scans_processed_;

  const Pose2 guess = PredictPose(odometry, &report);
  // A faulty increment was dropped (PredictPose): that scan was not predicted by odometry.
  const bool odometry_predicted = odometry && !report.odometry_fault;
  const Pose2 previous = pose_;
  ToBasePoints(mount, &report.beams);

  if (static_cast<int>(base_points_.size()) < options_.min_valid_beams) {
    pose_ = guess;
    report.outcome = ScanOutcome::kTooFewPoints;
    AppendMessage(std::to_string(base_points_.size()) + " matchable beams, fewer than " +
                      std::to_string(options_.min_valid_beams),
                  &report.message);
    Track(odometry_predicted ? ScanEvidence::kOdometryOnly : ScanEvidence::kBlind, std::nan(""),
          &report);
  } else if (!map_initialized_) {
    pose_ = guess;
    report.node_id = InsertIntoMap(mount, scan.stamp, &report.updated_region);
    // What a match scores on this map, so the recovery can judge the very next scan's match.
    average_score_ = Match(pose_).mean_occupancy;
    report.outcome = ScanOutcome::kInitialized;
    report.map_updated = true;
  } else {
    if (options_.map_with_known_poses) {
      pose_ = guess;
      report.outcome = ScanOutcome::kKnownPose;
    } else {
      const bool lost = tracking_.state() == TrackingState::kLost;
      report.match = lost ? MatchWhileLost(guess, odometry_predicted, &report)
                          : MatchWithRecovery(guess, odometry_predicted,
                                              &report.recovered, &report.message);
      if (!lost && pose_unconfirmed_) ConfirmLoadedPose(guess, &report);
      JudgeMatch(guess, odometry_predicted, &report);
      report.outcome = ScanOutcome::kMatched;
    }
    // Known poses need no map to match against, so every scan goes in (as hector does).
    if (options_.map_with_known_poses ||
        ((ShouldUpdateMap() || MapGoingStale(report)) &&
         MapMayChange(report, odometry_predicted, guess))) {
      if (defer_map_update) {
        deferred_ = DeferredInsertion{mount, scan.stamp, pose_};
        report.map_update_deferred = true;
      } else {
        report.node_id = InsertIntoMap(mount, scan.stamp, &report.updated_region);
        report.map_updated = true;
      }
    }
  }
  FinishScan(previous, scan.stamp, odometry_predicted, &report);
  report.global_pose = GlobalPose();
  // The match's covariance is in the front end's frame; global_pose is in the map frame.
  if (report.pose_from_scan) {
    report.covariance =
        RotatedCovariance(report.covariance, report.global_pose.theta - report.pose.theta);
  }
  return report;
}

}  // namespace hex_slam
