// What every scan matcher takes and returns, whatever its lattice, and the Gauss–Newton matcher
// written once over the lattice.
#ifndef HEX_SLAM_MATCHING_SCAN_MATCHER_H_
#define HEX_SLAM_MATCHING_SCAN_MATCHER_H_

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {

// Gauss–Newton controls per pyramid level. hector_mapping hard-codes 3 iterations on coarse
// levels and 5 on the finest with no convergence test; here they are named and tested.
struct ScanMatcherOptions {
  int max_iterations_coarse = 5;
  int max_iterations_fine = 10;
  // A level stops once a step moves less than this fraction of the level's cell spacing and
  // turns less than its angle tolerance (LevelAngleTolerance).
  double translation_tolerance_cells = 0.02;
  double angle_tolerance = 3e-4;  // rad
  // Per-iteration clamps: Gauss–Newton on a saturated map can propose huge steps.
  double max_angle_step = 0.2;               // rad, as hector's ScanMatcher
  double max_translation_step_cells = 2.0;   // in cells of the level being matched
  // On coarse levels consecutive endpoints closer than this many coarse cells are merged, so a
  // level costs what its resolution can use. 0 keeps every endpoint.
  double coarse_point_spacing_cells = 0.5;
  // Read the map at sub-cell resolution: each cell remembers where in it its endpoints fell
  // (GridMap's CellHits), and the matcher pulls endpoints to where walls were seen instead of
  // to the centres of their cells, which removes a bias of up to half a cell per wall. Used on
  // every level but the coarsest (which is for the basin, not the last centimetre). Off is the
  // paper's method on the hex lattice and hector_mapping's on the square one.
  bool subcell_offsets = true;
  // Evaluate the cost after a step that met the tolerances, and halve or reject it if the cost
  // rose, as after every other step. Off, such a step is taken as it is and the level ends: it
  // is too small to overshoot, and checking it costs one more pass over the points per level
  // (a fifth of the matching time). On is the method as hector's baseline runs it.
  bool verify_converged_step = false;
  // A turn converges as a translation does: when it moves the scan's mean endpoint less than
  // the level's translation tolerance, i.e. the angle tolerance is that tolerance over the mean
  // range. It grows with the level's cells (a coarse level only has to hand the next a pose in
  // its basin) and loosens in small rooms, where a fixed 0.3 mrad was far below what the cells
  // resolve. Off: angle_tolerance on every level, the method as hector's baseline runs it.
  bool angle_tolerance_from_range = true;
  // The coarsest level reads the plain map (no sub-cell offsets there, see above), whose optimum
  // is off by up to half of its cell: it exists to bring a pose that is far off into the finer
  // levels' basin. A move of it that displaces no endpoint by more than this many of its cells
  // is dropped, so the finer levels start from the guess rather than from that bias, which they
  // would spend passes undoing. 0 (the default) keeps every move. 0.25 makes the simulated
  // benchmark's 0.04 m² rows 30% faster at equal accuracy but the Intel log's relations 1 mm
  // worse (docs/benchmark.md), so it is left to setups like the former.
  double coarsest_min_move_cells = 0.0;
  // Robust loss (Cauchy), on every level but the coarsest: an endpoint whose residual r = 1 - M is large weighs
  // 1 / (1 + (r / robust_loss_scale)²) in the normal equations, and the cost each level
  // minimises is Σ c² ln(1 + (r/c)²) instead of Σ r², so returns the map does not explain (a
  // person, a ghost ring at the lidar's maximum range that travels with it) stop pulling the pose.
  // r lies in [0, 1]: a return on a well-known wall has r ≈ 0.1–0.3, one in free space r ≈ 1.
  // 0 turns it off (plain least squares, hector's method). 0.3 makes the Intel log's relations
  // 8–11% better (relations, with and without odometry) and the simulated maze no worse.
  double robust_loss_scale = 0.3;  // 0, or at least kMinRobustLossScale
  // A match that starts from odometry's prediction is pulled towards its position: every level's
  // cost gains w·N·|t - t_odometry|² (N the level's endpoints, t in metres), as Cartographer's
  // ceres_scan_matcher.translation_weight (10 there, on a cost normalised by N: 100 per m²).
  // Along a direction the scan leaves weak (a corridor, a wall seen at a grazing angle) the match
  // then keeps odometry's position instead of wandering. Odometry's heading is not held: it is
  // what wheel odometry gets wrong, and a rotation weight of 30 per rad² made the Intel log's
  // relations worse, 100 lost it. Measured (Intel relations over ten nudged runs, median; the
  // simulated building loop with odometry, 8 seeds): 0 gives 0.01560 m and seed 4 lost with loop
  // closure; 3 gives 0.01494 m and no seed lost (2: 0.01507 m). Heavier pulls carry odometry's
  // 1 % scale error into the front end (5, with the heading held too, stop 21: the building's
  // seeds 1-3 without loop closure 0.118/0.110/0.140 m against 0.124/0.071/0.083 m), and so
  // does 3 with odometry four times worse than that (twice the error: docs/ros.md). 0 turns it
  // off (hector's method); set it so for poor odometry.
  double odometry_translation_weight = 3.0;  // per endpoint and m²
  // The scale a level uses: none on the coarsest, whose job is to pull a pose that is far off
  // into the finer levels' basin, where every endpoint still has a large residual.
  double LevelRobustLossScale(bool coarsest) const { return coarsest ? 0.0 : robust_loss_scale; }

  // The angle tolerance on a level with this translation tolerance (m), for a scan whose
  // endpoints lie `mean_range` (m) from the robot on average.
  double LevelAngleTolerance(double translation_tolerance, double mean_range) const {
    return angle_tolerance_from_range && mean_range > 0.0 ? translation_tolerance / mean_range
                                                          : angle_tolerance;
  }

  // Empty when valid; otherwise one message per bad field, naming it.
  std::vector<std::string> Validate() const;
};

// Residuals lie in [0, 1]; a scale below this would weigh every endpoint off a wall as nothing,
// and its 1/c² would leave the range where the cost's products (NormalSums) are exact.
constexpr double kMinRobustLossScale = 1e-6;

// The per-endpoint weight and cost of ScanMatcherOptions::robust_loss_scale, shared by both
// lattices' linearisations. Inline: it is evaluated for every endpoint of every pass.
class RobustKernel {
 public:
  explicit RobustKernel(double scale) : inv_scale_sq_(scale > 0.0 ? 1.0 / (scale * scale) : 0.0) {}
  bool enabled() const { return inv_scale_sq_ > 0.0; }
  // 1 + r²/c², the reciprocal of the weight (1 when off).
  double Factor(double residual) const { return 1.0 + residual * residual * inv_scale_sq_; }
  // The IRLS weight ρ'(r) / (2r): 1 for plain least squares.
  double Weight(double residual) const { return 1.0 / Factor(residual); }
  // ρ(r), equal to r² for small r (and exactly r² when off).
  double Cost(double residual) const {
    const double u = residual * residual;
    return enabled() ? std::log1p(u * inv_scale_sq_) / inv_scale_sq_ : u;
  }
  // Σ ρ(r) over residuals whose factors multiply to `product` (kernel on): ρ(r) = c² log Factor(r),
  // so a sum of costs takes one logarithm instead of one per residual.
  double CostOfProduct(double product) const { return std::log(product) / inv_scale_sq_; }

 private:
  double inv_scale_sq_;
};

// hector_mapping's method as this package runs it, the baseline of every comparison: no sub-cell
// offsets, every step verified, one fixed angle tolerance, every coarse move kept. The
// rest of `options` is kept.
void UseHectorsMethod(ScanMatcherOptions* options);

struct LevelReport {
  int iterations = 0;
  int linearizations = 0;  // passes over the points (one per cost evaluation)
  bool move_dropped = false;  // the coarsest level's move was below coarsest_min_move_cells
  int rejected_steps = 0;
  int points = 0;
  bool converged = false;
  double cost = 0.0;
};

struct MatchResult {
  Pose2 pose;
  // Gauss–Newton Hessian at the result on the finest level, in (x, y, theta) units.
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  // The pose's covariance (m², rad²): residual variance times the Hessian's inverse.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  double cost = 0.0;  // Σ ρ(1 - M) over the finest level's endpoints: Σ (1 - M)² without a robust loss
  double mean_occupancy = 0.0;  // mean M at the endpoints: 1 means every one lies on a wall
  int num_points = 0;
  std::vector<LevelReport> levels;  // finest first
};

// Where a match's starting pose came from: odometry's prediction is also a measurement the match
// is pulled towards (ScanMatcherOptions::odometry_translation_weight); any other guess is only a
// starting point.
enum class GuessSource { kPrediction, kOdometry };

// The variance (m² or rad²) reported along a direction nothing constrains.
constexpr double kUnconstrainedVariance = 1e3;

// Residual variance × H⁻¹; kUnconstrainedVariance along directions where H is (near) singular.
Eigen::Matrix3d CovarianceFromHessian(const Eigen::Matrix3d& hessian, double cost, int points);

// The farthest any of `points` (robot frame; `reach` is their largest norm) moves between the
// robot poses `from` and `to`, bounded by the translation plus the turn times the reach.
double EndpointMoveBound(const Pose2& from, const Pose2& to, double reach);
double Reach(const std::vector<Eigen::Vector2d>& points);
// The points' mean norm (0 for none).
double MeanRange(const std::vector<Eigen::Vector2d>& points);

// Σ w JᵀJ, Σ w Jᵀr, Σ ρ(r) and Σ M at one state of size N, with r_i = 1 - M(S_i(state)), over
// `count` endpoints.
template <int N>
struct NormalEquations {
  Eigen::Matrix<double, N, N> hessian = Eigen::Matrix<double, N, N>::Zero();
  Eigen::Matrix<double, N, 1> gradient = Eigen::Matrix<double, N, 1>::Zero();
  double cost = 0.0;
  double sum_value = 0.0;
  int count = 0;
};

// What ScanMatcher needs of a lattice, specialised beside each lattice's linearisation
// (hex_scan_matcher.h, square_scan_matcher.h): Point (an endpoint as the linearisation reads
// it), State (the pose as Gauss–Newton moves it, heading last), Equations, and static
// ToPoint, FromPose, ToPose, Linearize, Solve, TranslationLength (of a step, in metres), Add (a
// step to a state) and PoseHessian (the Hessian in (x, y, θ)).
template <class Lattice>
struct ScanMatcherTraits;

// Gauss–Newton scan-to-map matching coarse to fine over a map pyramid of either lattice: on
// each level the endpoints thinned to its resolution, iterations up to its cap, sub-cell
// offsets and the robust loss on all but the coarsest; the result from the finest level.
// HexScanMatcher is the paper's (MATH.md §6), SquareScanMatcher hector_mapping's.
template <class Lattice>
class ScanMatcher {
 public:
  explicit ScanMatcher(const ScanMatcherOptions& options) : options_(options) {}

  // `points`: valid endpoints in the robot (base) frame. Starts from `guess`. The result's
  // Hessian, cost and covariance are the map's alone, without the pull towards odometry.
  MatchResult Match(const MapPyramid<Lattice>& maps, const std::vector<Eigen::Vector2d>& points,
                    const Pose2& guess, GuessSource source = GuessSource::kPrediction) const;

 private:
  ScanMatcherOptions options_;
  // A level's endpoints as the lattice reads them; scratch kept between calls to save allocations.
  mutable std::vector<typename ScanMatcherTraits<Lattice>::Point> scan_;
};

// Calls `keep(p)` for each endpoint no closer than `min_spacing` to the last one kept (scan
// order); for all of them if min_spacing <= 0.
template <class Keep>
void ForEachKeptEndpoint(const std::vector<Eigen::Vector2d>& points, double min_spacing,
                         Keep keep) {
  const double min_sq = min_spacing * min_spacing;
  const Eigen::Vector2d* last = nullptr;
  for (const Eigen::Vector2d& p : points) {
    if (min_spacing > 0.0 && last != nullptr && (p - *last).squaredNorm() < min_sq) continue;
    keep(p);
    last = &p;
  }
}

// The endpoints ForEachKeptEndpoint keeps, copied.
void DecimateScan(const std::vector<Eigen::Vector2d>& points, double min_spacing,
                  std::vector<Eigen::Vector2d>* kept);

}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_SCAN_MATCHER_H_
