#include "hex_slam/matching/correlative_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace {

// An angular step never coarser than this, whatever the scan's extent (rad).
constexpr double kMaxAngularStep = 0.05;
// The angular step moves the endpoint at this quantile of the ranges by one translation step:
// the farthest few may move more, the bulk of the scan does not.
constexpr double kAngularStepRangeQuantile = 0.75;
// Each retry of a window over its budget coarsens the steps this much more.
constexpr double kCoarseningIncrement = 1.05;

// `scan` turned by `theta` about the robot's origin, into `rotated` (as long as `scan`).
void Rotate(const std::vector<Eigen::Vector2d>& scan, double theta,
            std::vector<Eigen::Vector2d>* rotated) {
  const double c = std::cos(theta), s = std::sin(theta);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    (*rotated)[i] = {c * scan[i].x() - s * scan[i].y(), s * scan[i].x() + c * scan[i].y()};
  }
}

// No cell's probability exceeds 1, so a candidate whose sum so far plus 1 for each point left
// falls short of the best mean cannot win; the margin covers the sum's rounding.
constexpr double kMaxCellProbability = 1.0;
constexpr double kPruneMargin = 1e-9;
constexpr std::size_t kPruneCheckEvery = 8;

// The mean probability of the cells `points` (already rotated) fall in once shifted by `shift`,
// or nullopt as soon as it is sure to stay below `must_reach` (checked every few points).
template <class Lattice>
std::optional<double> MeanProbabilityReaching(const GridMap<Lattice>& grid,
                                              const std::vector<Eigen::Vector2d>& points,
                                              const Eigen::Vector2d& shift, double must_reach) {
  const double n = static_cast<double>(points.size());
  const double needed = must_reach * n - kPruneMargin * n;
  double sum = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    sum += grid.Probability(grid.lattice().CellOf(points[i] + shift));
    if ((i + 1) % kPruneCheckEvery == 0 &&
        sum + kMaxCellProbability * static_cast<double>(points.size() - i - 1) < needed) {
      return std::nullopt;
    }
  }
  return sum / points.size();
}

template <class Lattice>
double MeanProbability(const GridMap<Lattice>& grid, const std::vector<Eigen::Vector2d>& points,
                       const Eigen::Vector2d& shift) {
  return *MeanProbabilityReaching(grid, points, shift,
                                  -std::numeric_limits<double>::infinity());
}

// The search's grid: its steps, how many of them on each side of the centre, and the poses.
struct SearchGrid {
  double linear_step = 0.0, angular_step = 0.0;
  double half_linear = 0.0, half_angular = 0.0;  // steps on each side of the centre
  double poses = 0.0;  // counted in doubles: a window of any size is refused, not overflowed
  double coarsening = 1.0;
};

SearchGrid GridOf(double linear_step, double angular_step, double coarsening,
                  const CorrelativeSearchOptions& options) {
  SearchGrid g;
  g.coarsening = coarsening;
  g.linear_step = linear_step * coarsening;
  g.angular_step = angular_step * coarsening;
  g.half_linear = std::floor(options.linear_window / g.linear_step);
  g.half_angular = std::floor(options.angular_window / g.angular_step);
  g.poses =
      (2.0 * g.half_angular + 1.0) * (2.0 * g.half_linear + 1.0) * (2.0 * g.half_linear + 1.0);
  return g;
}

// The grid the options ask for (the angular step moves the endpoint at the range quantile by one
// translation step), or, when it takes more poses than the budget, the least coarsened one up
// to max_step_coarsening that fits; if none does, the grid as asked (to be refused).
SearchGrid GridWithinBudget(const std::vector<Eigen::Vector2d>& scan, double spacing,
                            const CorrelativeSearchOptions& options) {
  std::vector<double> ranges;
  for (const Eigen::Vector2d& p : scan) ranges.push_back(p.norm());
  const std::size_t q = static_cast<std::size_t>(kAngularStepRangeQuantile * (ranges.size() - 1));
  std::nth_element(ranges.begin(), ranges.begin() + q, ranges.end());
  const double linear_step = options.step_cells * spacing;
  const double angular_step = std::max(
      kMinCorrelativeAngularStep,
      std::min(kMaxAngularStep, linear_step / std::max(ranges[q], linear_step)));
  const SearchGrid asked = GridOf(linear_step, angular_step, 1.0, options);
  const double budget = static_cast<double>(options.max_candidates);
  if (!(asked.poses > budget && std::isfinite(asked.poses))) return asked;
  // The poses grow as the cube of 1/step: all three steps are coarsened alike by the cube root
  // of the excess, then a little more while the floors still leave the count over.
  for (double coarsening = std::cbrt(asked.poses / budget);
       coarsening <= options.max_step_coarsening; coarsening *= kCoarseningIncrement) {
    const SearchGrid coarser = GridOf(linear_step, angular_step, coarsening, options);
    if (coarser.poses <= budget) return coarser;
  }
  return asked;
}

}  // namespace

std::vector<std::string> CorrelativeSearchOptions::Validate() const {
  std::vector<std::string> errors;
  if (!(linear_window >= 0.0)) errors.push_back("recovery_linear_window must be >= 0");
  if (!(angular_window >= 0.0)) errors.push_back("recovery_angular_window must be >= 0");
  if (!(step_cells > 0.0)) errors.push_back("recovery_step_cells must be > 0");
  if (!(point_spacing_cells >= 0.0)) errors.push_back("recovery_point_spacing_cells must be >= 0");
  if (max_candidates < 1) errors.push_back("recovery_max_candidates must be >= 1");
  if (!(max_step_coarsening >= 1.0 && std::isfinite(max_step_coarsening))) {
    errors.push_back("the correlative search's step coarsening must be finite and >= 1");
  }
  return errors;
}

template <class Lattice>
CorrelativeResult SearchCorrelative(const GridMap<Lattice>& grid,
                                    const std::vector<Eigen::Vector2d>& points,
                                    const Pose2& centre, const CorrelativeSearchOptions& options) {
  CorrelativeResult best;
  best.pose = centre;
  const double spacing = grid.lattice().spacing();
  std::vector<Eigen::Vector2d> scan;
  DecimateScan(points, options.point_spacing_cells * spacing, &scan);
  if (scan.empty()) return best;

  const SearchGrid steps = GridWithinBudget(scan, spacing, options);
  if (!(steps.poses <= static_cast<double>(options.max_candidates))) {
    std::ostringstream s;
    s << "the search window takes " << steps.poses
      << " poses, more than recovery_max_candidates (" << options.max_candidates << ")";
    best.refused = s.str();
    return best;
  }
  best.step_coarsening = steps.coarsening;
  const double linear_step = steps.linear_step, angular_step = steps.angular_step;
  const int n_linear = static_cast<int>(steps.half_linear);
  const int n_angular = static_cast<int>(steps.half_angular);

  best.score = -1.0;
  double best_move = 0.0;  // among equal scores, the candidate nearest the centre wins
  std::vector<Eigen::Vector2d> rotated(scan.size());
  // The centre is one of the candidates, so the winner scores at least what it does: anything
  // sure to score less is dropped early from the start, not only once the scan order reaches a
  // good candidate. (The centre itself is scored again in its turn, to the same value.)
  Rotate(scan, centre.theta, &rotated);
  const double centre_score = MeanProbability(grid, rotated, centre.translation());
  for (int ia = -n_angular; ia <= n_angular; ++ia) {
    const double theta = centre.theta + ia * angular_step;
    Rotate(scan, theta, &rotated);
    for (int ix = -n_linear; ix <= n_linear; ++ix) {
      for (int iy = -n_linear; iy <= n_linear; ++iy) {
        const Eigen::Vector2d t(centre.x + ix * linear_step, centre.y + iy * linear_step);
        ++best.candidates;
        // A candidate that cannot reach the best score cannot win, nor tie.
        const std::optional<double> reached =
            MeanProbabilityReaching(grid, rotated, t, std::max(best.score, centre_score));
        if (!reached) continue;
        const double score = *reached;
        const double move = std::abs(ia) + std::abs(ix) + std::abs(iy);
        if (score > best.score || (score == best.score && move < best_move)) {
          best.score = score;
          best_move = move;
          best.pose = Pose2(t.x(), t.y(), NormalizeAngle(theta));
        }
      }
    }
  }
  return best;
}

template <class Lattice>
double CorrelativeScore(const GridMap<Lattice>& grid, const std::vector<Eigen::Vector2d>& points,
                        const Pose2& pose, const CorrelativeSearchOptions& options) {
  std::vector<Eigen::Vector2d> scan;
  DecimateScan(points, options.point_spacing_cells * grid.lattice().spacing(), &scan);
  if (scan.empty()) return 0.0;
  Rotate(scan, pose.theta, &scan);
  return MeanProbability(grid, scan, pose.translation());
}

template CorrelativeResult SearchCorrelative(const GridMap<HexLattice>&,
                                             const std::vector<Eigen::Vector2d>&, const Pose2&,
                                             const CorrelativeSearchOptions&);
template CorrelativeResult SearchCorrelative(const GridMap<SquareLattice>&,
                                             const std::vector<Eigen::Vector2d>&, const Pose2&,
                                             const CorrelativeSearchOptions&);
template double CorrelativeScore(const GridMap<HexLattice>&, const std::vector<Eigen::Vector2d>&,
                                 const Pose2&, const CorrelativeSearchOptions&);
template double CorrelativeScore(const GridMap<SquareLattice>&,
                                 const std::vector<Eigen::Vector2d>&, const Pose2&,
                                 const CorrelativeSearchOptions&);

}  // namespace hex_slam
