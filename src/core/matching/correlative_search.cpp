#include "hex_slam/matching/correlative_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/geometry/pose2.h"
#include "hex_slam/matching/precomputation_grid.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/matching/step_bounds.h"
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

// The sum of value(i) for i < count, or nullopt as soon as it is sure to stay below `needed`:
// no value exceeds `max_value` (checked every few terms). Summed in order, so the same values
// give the same sum to the last bit.
template <class T, class Value>
std::optional<T> SumReaching(std::size_t count, const Value& value, T max_value, double needed) {
  T sum = 0;
  for (std::size_t i = 0; i < count; ++i) {
    sum += value(i);
    if ((i + 1) % kPruneCheckEvery == 0 &&
        static_cast<double>(sum + max_value * static_cast<T>(count - i - 1)) < needed) {
      return std::nullopt;
    }
  }
  return sum;
}

// The mean probability of the cells `points` (already rotated) fall in once shifted by `shift`,
// or nullopt as soon as it is sure to stay below `must_reach` (checked every few points).
template <class Lattice>
std::optional<double> MeanProbabilityReaching(const GridMap<Lattice>& grid,
                                              const std::vector<Eigen::Vector2d>& points,
                                              const Eigen::Vector2d& shift, double must_reach) {
  const double n = static_cast<double>(points.size());
  const std::optional<double> sum = SumReaching<double>(
      points.size(),
      [&](std::size_t i) { return grid.Probability(grid.lattice().CellOf(points[i] + shift)); },
      kMaxCellProbability, must_reach * n - kPruneMargin * n);
  if (!sum) return std::nullopt;
  return *sum / n;
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

// Branch and bound needs no more depth than this: blocks of 64 × 64 steps, 6.4 m at the
// default 0.1 m; a wider window starts from several blocks per heading.
constexpr int kMaxBoundDepth = 6;
// A block is dropped only when its bound falls short of the best score by more than the
// rounding of a mean over millions of endpoints: a tie with the best is always searched.
constexpr double kBoundRelativeSlack = 1e-9;
// A window whose poses times endpoints fall below this many times its pixels is scored pose by
// pose instead (a small window around a prediction on a large map). Either way the result is
// the same; this is where the two took about as long over the Intel log without odometry with
// hector's settings (0.5 against 1 and 2: per scan p99 2.0 against 2.2 and 2.8 ms).
constexpr double kBoundsMinWorkPerPixel = 0.5;
// The most pixels the bounds may take (a byte each, once per depth): beyond, pose by pose. A
// 0.1 m step covers 200 m x 200 m within it; only a step made very fine on a large map needs more.
constexpr double kMaxBoundPixels = 4e6;

// The exhaustive search over the grid `steps` around `centre`: the same winner as scoring every
// pose (the highest mean probability; among equal scores the fewest steps from the centre, then
// the first in heading, x, y order). A large window is searched by branch and bound, without
// scoring the blocks of poses whose upper bound cannot reach the best so far (step_bounds.h).
// One heading's turned scan is held at a time, so memory does not grow with the headings.
template <class Lattice>
class WindowSearch {
 public:
  WindowSearch(const GridMap<Lattice>& grid, const std::vector<Eigen::Vector2d>& scan,
               const Pose2& centre, const SearchGrid& steps, bool may_bound)
      : may_bound_(may_bound),
        grid_(grid),
        scan_(scan),
        centre_(centre),
        step_(steps.linear_step),
        angular_step_(steps.angular_step),
        n_linear_(static_cast<int>(steps.half_linear)),
        n_angular_(static_cast<int>(steps.half_angular)),
        width_(2 * n_linear_ + 1),
        poses_(steps.poses),
        rotated_(scan.size()) {}

  // The best pose; `best` comes in holding the centre and its score. Returns whether the window
  // was searched by branch and bound.
  bool Run(CorrelativeResult* best) {
    best_ = best;
    best_move_ = 0;
    best_order_ = OrderOf(n_angular_, 0, 0);
    const Eigen::AlignedBox2d reach = Reach();
    const Eigen::AlignedBox2d bounded = matching::BoundedBox(grid_, reach);
    // No written cell within reach: every endpoint of every pose falls on an unknown cell, so
    // every pose scores what the centre does, and the centre wins the tie.
    if (bounded.isEmpty()) return false;
    const double pixels = bounded.volume() / (step_ * step_);
    if (!may_bound_ || !(pixels <= kMaxBoundPixels) ||
        poses_ * static_cast<double>(scan_.size()) < kBoundsMinWorkPerPixel * pixels) {
      ScoreEveryPose();
      return false;
    }
    const int depth = DepthFor(width_);
    bounds_.emplace(matching::PixelBounds(grid_, step_, reach), depth);
    const int size = 1 << depth;
    std::vector<Block> top;
    for (int h = 0; h <= 2 * n_angular_; ++h) {
      Load(h);
      for (int x = -n_linear_; x <= n_linear_; x += size) {
        for (int y = -n_linear_; y <= n_linear_; y += size) AddIfReaching({h, x, y, depth}, &top);
      }
    }
    SortByBound(&top);
    for (const Block& block : top) {
      if (static_cast<double>(block.bound) < Needed()) break;  // nor can any after it
      Load(block.heading);
      Explore(block);
    }
    return true;
  }

 private:
  // The poses of heading h (0 at -n_angular steps) shifted by [x, x + 2^depth) × [y, ...) steps.
  struct Block {
    int heading, x, y, depth;
    long bound = 0;  // sum of the endpoints' codes
  };

  static int DepthFor(int width) {
    int depth = 0;
    while ((1 << depth) < width && depth < kMaxBoundDepth) ++depth;
    return depth;
  }

  static void SortByBound(std::vector<Block>* blocks) {
    std::sort(blocks->begin(), blocks->end(),
              [](const Block& a, const Block& b) { return a.bound > b.bound; });
  }

  // Every endpoint of every candidate lies in this box, and the bounds are built over it alone.
  // An endpoint at range r turned anywhere within the heading window stays within r·a of where
  // the centre's heading puts it (a chord is shorter than its arc); the shifts add the linear
  // window and a step. The square round the farthest endpoint bounds it too, for wide windows.
  // A scan seen over half a turn or less fills a fraction of that square: without odometry the
  // bounds over the whole square were a sixth of the scan path's time (Intel subset).
  Eigen::AlignedBox2d Reach() const {
    const double turn = n_angular_ * angular_step_;
    const double shift = (n_linear_ + 1) * step_;
    const PointTransform at_centre(centre_);
    double farthest = 0.0;
    Eigen::AlignedBox2d swept;
    for (const Eigen::Vector2d& p : scan_) {
      const double r = p.norm();
      farthest = std::max(farthest, r);
      const Eigen::Vector2d q = at_centre(p);
      const Eigen::Vector2d margin = Eigen::Vector2d::Constant(r * turn + shift);
      swept.extend(q - margin);
      swept.extend(q + margin);
    }
    const double r = farthest + shift;
    const Eigen::AlignedBox2d square(Eigen::Vector2d(centre_.x - r, centre_.y - r),
                                     Eigen::Vector2d(centre_.x + r, centre_.y + r));
    return swept.intersection(square);
  }

  double ThetaOf(int heading) const {
    return centre_.theta + (heading - n_angular_) * angular_step_;
  }

  // The scan turned to `heading` and, with bounds, each endpoint's pixel at the centre.
  void Load(int heading) {
    if (heading == loaded_) return;
    loaded_ = heading;
    Rotate(scan_, ThetaOf(heading), &rotated_);
    if (!bounds_) return;
    pixels_.clear();
    for (const Eigen::Vector2d& p : rotated_) {
      pixels_.push_back(matching::PixelOf(p + centre_.translation(), step_));
    }
  }

  void ScoreEveryPose() {
    for (int h = 0; h <= 2 * n_angular_; ++h) {
      Load(h);
      for (int x = -n_linear_; x <= n_linear_; ++x) {
        for (int y = -n_linear_; y <= n_linear_; ++y) Score({h, x, y, 0});
      }
    }
  }

  long OrderOf(int heading, int x, int y) const {
    return (static_cast<long>(heading) * width_ + (x + n_linear_)) * width_ + (y + n_linear_);
  }

  // The code sum a block must reach to hold a pose that scores at least the best.
  double Needed() const {
    return best_->score * matching::kValueScale * static_cast<double>(scan_.size()) *
           (1.0 - kBoundRelativeSlack);
  }

  // Appends the block (of the loaded heading) with its bound, unless the bound falls short of
  // the best.
  void AddIfReaching(Block block, std::vector<Block>* out) const {
    const matching::PrecomputationGrid& level = bounds_->Get(block.depth);
    const Eigen::Array2i shift(block.x, block.y);
    const double needed = Needed();
    const std::optional<long> sum = SumReaching<long>(
        pixels_.size(), [&](std::size_t i) { return level.CodeAt(pixels_[i] + shift); },
        static_cast<long>(matching::kValueScale), needed);
    if (!sum || static_cast<double>(*sum) < needed) return;
    block.bound = *sum;
    out->push_back(block);
  }

  // The block (of the loaded heading) split, most promising part first, down to single poses.
  void Explore(const Block& block) {
    if (block.depth == 0) {
      Score(block);
      return;
    }
    const int half = 1 << (block.depth - 1);
    std::vector<Block> children;
    for (const int x : {block.x, block.x + half}) {
      for (const int y : {block.y, block.y + half}) {
        if (x <= n_linear_ && y <= n_linear_) {
          AddIfReaching({block.heading, x, y, block.depth - 1}, &children);
        }
      }
    }
    SortByBound(&children);
    for (const Block& child : children) {
      if (static_cast<double>(child.bound) < Needed()) return;
      Explore(child);
    }
  }

  // One pose of the loaded heading.
  void Score(const Block& pose) {
    const Eigen::Vector2d t(centre_.x + pose.x * step_, centre_.y + pose.y * step_);
    const std::optional<double> reached =
        MeanProbabilityReaching(grid_, rotated_, t, best_->score);
    if (!reached) return;
    const int move = std::abs(pose.heading - n_angular_) + std::abs(pose.x) + std::abs(pose.y);
    const long order = OrderOf(pose.heading, pose.x, pose.y);
    const bool wins = *reached > best_->score ||
                      (*reached == best_->score &&
                       (move < best_move_ || (move == best_move_ && order < best_order_)));
    if (!wins) return;
    best_->score = *reached;
    best_->pose = Pose2(t.x(), t.y(), NormalizeAngle(ThetaOf(pose.heading)));
    best_move_ = move;
    best_order_ = order;
  }

  const bool may_bound_;
  const GridMap<Lattice>& grid_;
  const std::vector<Eigen::Vector2d>& scan_;
  const Pose2 centre_;
  const double step_, angular_step_;
  const int n_linear_, n_angular_, width_;
  const double poses_;
  std::optional<matching::PrecomputationGridStack> bounds_;
  int loaded_ = -1;
  std::vector<Eigen::Vector2d> rotated_;  // the scan turned to the loaded heading
  std::vector<Eigen::Array2i> pixels_;    // its endpoints' pixels at the centre's translation
  CorrelativeResult* best_ = nullptr;
  int best_move_ = 0;
  long best_order_ = 0;
};

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
  best.linear_step = steps.linear_step;
  best.angular_step = steps.angular_step;
  best.candidates = static_cast<int>(steps.poses);
  // The centre is one of the candidates and the nearest to itself: the winner scores at least
  // what it does, and it wins every tie.
  std::vector<Eigen::Vector2d> rotated(scan.size());
  Rotate(scan, centre.theta, &rotated);
  best.score = MeanProbability(grid, rotated, centre.translation());
  best.pose = Pose2(centre.x, centre.y, NormalizeAngle(centre.theta));
  best.branch_and_bound =
      WindowSearch<Lattice>(grid, scan, centre, steps, options.branch_and_bound).Run(&best);
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
