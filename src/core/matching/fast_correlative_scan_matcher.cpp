#include "hex_slam/matching/fast_correlative_scan_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/lattice_axes.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace matching {
namespace {

// The deepest precomputation offered: 2^15 cells is a window of kilometres at any useful spacing,
// and the grids' extra rows and columns grow with it.
constexpr int kMaxBranchAndBoundDepth = 16;
// A window offset no map reaches; the full-submap search starts from it and cuts to the map.
constexpr int kUnboundedOffset = std::numeric_limits<int>::max() / 4;

struct Candidate {
  int scan = 0;  // index into the rotations
  Eigen::Array2i offset = Eigen::Array2i::Zero();
  double score = 0.0;
};

// Slack on heading comparisons between rotations (rad): far below any angular step.
constexpr double kHeadingRounding = 1e-9;

bool ByScoreDescending(const Candidate& a, const Candidate& b) { return a.score > b.score; }

// The poses of one peak: within `cells` (per lattice axis) of its best offset and `angle` (rad)
// of its heading. Headings compare as angles: a search over every heading has rotations on both
// sides of ±π that are the same pose.
struct PeakZone {
  double theta = 0.0;
  Eigen::Array2i offset = Eigen::Array2i::Zero();
  int cells = 0;
  double angle = 0.0;

  // Whether every offset of the block [offset, offset + width)² at heading `block_theta` is in it.
  bool Covers(double block_theta, const Eigen::Array2i& block, int width) const {
    return std::abs(NormalizeAngle(block_theta - theta)) <= angle &&
           (block >= offset - cells).all() && (block + width - 1 <= offset + cells).all();
  }
};

double Score(const PrecomputationGrid& grid, const DiscreteScan& scan, const Eigen::Array2i& offset) {
  // Summed as the grid's integer codes: exact, and no conversion per endpoint.
  long sum = 0;
  if (grid.Contains(scan.lowest + offset, scan.highest + offset)) {
    // The whole scan on the grid (most candidates): the same reads without a bounds check each.
    const Eigen::Array2i base = offset - grid.origin();
    const std::ptrdiff_t width = grid.size().x();
    const std::uint8_t* values = grid.data();
    for (const Eigen::Array2i& cell : scan.cells) {
      sum += values[(cell.y() + base.y()) * width + (cell.x() + base.x())];
    }
  } else {
    for (const Eigen::Array2i& cell : scan.cells) sum += grid.CodeAt(cell + offset);
  }
  return static_cast<double>(sum) / (kValueScale * static_cast<double>(scan.cells.size()));
}

// Cuts each rotation's offsets to those that leave some endpoint's row and column on the map's
// box of known cells (Cartographer's ShrinkToFit): beyond them every endpoint is unknown. Keeps
// each rotation's box of cells for Score.
void ShrinkToFit(const PrecomputationGrid& cells, std::vector<DiscreteScan>* scans) {
  for (DiscreteScan& scan : *scans) {
    Eigen::Array2i lowest = scan.cells.front(), highest = scan.cells.front();
    for (const Eigen::Array2i& c : scan.cells) {
      lowest = lowest.min(c);
      highest = highest.max(c);
    }
    scan.min_offset = scan.min_offset.max(cells.origin() - highest);
    scan.max_offset = scan.max_offset.min(cells.last() - lowest);
    scan.lowest = lowest;
    scan.highest = highest;
  }
}

class BranchAndBound {
 public:
  // With `excluded`, the poses of that peak are left out (the runner-up search).
  BranchAndBound(const PrecomputationGridStack& grids, const std::vector<DiscreteScan>& scans,
                 const PeakZone* excluded = nullptr)
      : grids_(grids), scans_(scans), excluded_(excluded) {}

  std::vector<Candidate> CoarsestCandidates() {
    const int depth = grids_.max_depth();
    const int step = 1 << depth;
    std::vector<Candidate> out;
    for (int i = 0; i < static_cast<int>(scans_.size()); ++i) {
      const DiscreteScan& s = scans_[i];
      for (int x = s.min_offset.x(); x <= s.max_offset.x(); x += step) {
        for (int y = s.min_offset.y(); y <= s.max_offset.y(); y += step) {
          if (Excluded(i, Eigen::Array2i(x, y), step)) continue;
          out.push_back({i, Eigen::Array2i(x, y), 0.0});
        }
      }
    }
    ScoreAndSort(depth, &out);
    return out;
  }

  // The best candidate of depth 0 under `candidates` (sorted, best first) scoring above
  // min_score; its score is min_score when there is none.
  Candidate Search(const std::vector<Candidate>& candidates, int depth, double min_score) {
    if (depth == 0) {
      for (const Candidate& c : candidates) {
        if (c.score <= min_score) break;
        if (!Excluded(c.scan, c.offset, 1)) return c;
      }
      return Candidate{-1, Eigen::Array2i::Zero(), min_score};
    }
    Candidate best{-1, Eigen::Array2i::Zero(), min_score};
    const int half = 1 << (depth - 1);
    for (const Candidate& c : candidates) {
      // Sorted: no later block's bound beats the best pose found either.
      if (c.score <= best.score) break;
      const DiscreteScan& s = scans_[c.scan];
      std::vector<Candidate> children;
      for (int dx : {0, half}) {
        if (c.offset.x() + dx > s.max_offset.x()) break;
        for (int dy : {0, half}) {
          if (c.offset.y() + dy > s.max_offset.y()) break;
          const Eigen::Array2i child = c.offset + Eigen::Array2i(dx, dy);
          if (Excluded(c.scan, child, half)) continue;
          children.push_back({c.scan, child, 0.0});
        }
      }
      ScoreAndSort(depth - 1, &children);
      const Candidate found = Search(children, depth - 1, best.score);
      if (found.scan >= 0 && found.score > best.score) best = found;
    }
    return best;
  }

  long scored() const { return scored_; }

 private:
  bool Excluded(int scan, const Eigen::Array2i& block, int width) const {
    return excluded_ != nullptr && excluded_->Covers(scans_[scan].theta, block, width);
  }

  void ScoreAndSort(int depth, std::vector<Candidate>* candidates) {
    const PrecomputationGrid& grid = grids_.Get(depth);
    for (Candidate& c : *candidates) c.score = Score(grid, scans_[c.scan], c.offset);
    scored_ += static_cast<long>(candidates->size());
    std::sort(candidates->begin(), candidates->end(), ByScoreDescending);
  }

  const PrecomputationGridStack& grids_;
  const std::vector<DiscreteScan>& scans_;
  const PeakZone* excluded_;
  long scored_ = 0;
};

}  // namespace

std::vector<std::string> FastCorrelativeScanMatcherOptions::Validate() const {
  std::vector<std::string> errors;
  if (!(linear_search_window >= 0.0 && std::isfinite(linear_search_window))) {
    errors.push_back("loop_closure_linear_search_window must be finite and >= 0");
  }
  if (!(angular_search_window >= 0.0 && angular_search_window <= M_PI)) {
    errors.push_back("loop_closure_angular_search_window must lie in [0, pi]");
  }
  if (branch_and_bound_depth < 1 || branch_and_bound_depth > kMaxBranchAndBoundDepth) {
    errors.push_back("loop_closure_branch_and_bound_depth must lie in [1, " +
                     std::to_string(kMaxBranchAndBoundDepth) + "]");
  }
  if (!(unknown_probability >= 0.0 && unknown_probability <= 1.0)) {
    errors.push_back("loop_closure_unknown_probability must lie in [0, 1]");
  }
  if (!(ambiguity_ratio >= 0.0 && ambiguity_ratio <= 1.0)) {
    errors.push_back("loop_closure_ambiguity_ratio must lie in [0, 1]");
  }
  if (!(peak_radius >= 0.0 && std::isfinite(peak_radius))) {
    errors.push_back("loop_closure_peak_radius must be finite and >= 0");
  }
  if (!(peak_angle >= 0.0 && peak_angle <= M_PI)) {
    errors.push_back("loop_closure_peak_angle must lie in [0, pi]");
  }
  return errors;
}

double AngularSearchStep(double spacing, const std::vector<Eigen::Vector2d>& points) {
  double reach = spacing;  // a scan within one cell of the robot turns in steps of ~1 rad
  for (const Eigen::Vector2d& p : points) reach = std::max(reach, p.norm());
  return std::acos(1.0 - spacing * spacing / (2.0 * reach * reach));
}

template <class Lattice>
std::vector<DiscreteScan> DiscretizeScans(const Lattice& lattice, const Pose2& centre,
                                          const std::vector<Eigen::Vector2d>& points, double step,
                                          int half_count, const Eigen::Array2i& min_offset,
                                          const Eigen::Array2i& max_offset) {
  std::vector<DiscreteScan> scans(2 * half_count + 1);
  for (int i = -half_count; i <= half_count; ++i) {
    DiscreteScan& scan = scans[i + half_count];
    scan.theta = centre.theta + i * step;
    scan.min_offset = min_offset;
    scan.max_offset = max_offset;
    // Pose2 * p without its cosine and sine per point (the same arithmetic, so the same cells):
    // the rotations of the searches run over every point of every heading.
    const double c = std::cos(scan.theta);
    const double s = std::sin(scan.theta);
    scan.cells.reserve(points.size());
    for (const Eigen::Vector2d& p : points) {
      const Eigen::Vector2d world(centre.x + c * p.x() - s * p.y(), centre.y + s * p.x() + c * p.y());
      scan.cells.push_back(LatticeAxes<Lattice>::Of(lattice.CellOf(world)));
    }
  }
  return scans;
}

template <class Lattice>
FastCorrelativeScanMatcher<Lattice>::FastCorrelativeScanMatcher(
    const GridMap<Lattice>& grid, const FastCorrelativeScanMatcherOptions& options)
    : lattice_(grid.lattice()),
      basis_(LatticeAxes<Lattice>::Basis(grid.lattice())),
      options_(options),
      grids_(grid, options.branch_and_bound_depth - 1,
             static_cast<float>(options.unknown_probability)) {}

template <class Lattice>
std::vector<DiscreteScan> FastCorrelativeScanMatcher<Lattice>::Window(
    const Pose2& initial_pose, const std::vector<Eigen::Vector2d>& points, double linear_window,
    double angular_window) const {
  const double step = AngularSearchStep(lattice_.spacing(), points);
  const int half_count = static_cast<int>(std::ceil(angular_window / step));
  const Eigen::Array2i reach = OffsetsCovering(basis_, linear_window);
  return DiscretizeScans(lattice_, initial_pose, points, step, half_count, -reach, reach);
}

template <class Lattice>
std::optional<CorrelativeMatch> FastCorrelativeScanMatcher<Lattice>::Match(
    const Pose2& initial_pose, const std::vector<Eigen::Vector2d>& points,
    double min_score) const {
  return Match(initial_pose, points, min_score, options_.linear_search_window,
               options_.angular_search_window);
}

template <class Lattice>
std::optional<CorrelativeMatch> FastCorrelativeScanMatcher<Lattice>::Match(
    const Pose2& initial_pose, const std::vector<Eigen::Vector2d>& points, double min_score,
    double linear_window, double angular_window) const {
  if (points.empty() || !(linear_window >= 0.0 && std::isfinite(linear_window)) ||
      !(angular_window >= 0.0 && angular_window <= M_PI)) {
    return std::nullopt;
  }
  return Search(Window(initial_pose, points, linear_window, angular_window), initial_pose,
                min_score);
}

template <class Lattice>
std::optional<CorrelativeMatch> FastCorrelativeScanMatcher<Lattice>::MatchFullSubmap(
    const std::vector<Eigen::Vector2d>& points, double min_score) const {
  if (points.empty()) return std::nullopt;
  // Centred on the map's known cells, every heading, every offset (cut to the map below).
  const PrecomputationGrid& cells = grids_.cells();
  const Eigen::Array2i middle = cells.origin() + cells.size() / 2;
  const Eigen::Vector2d t = basis_ * middle.cast<double>().matrix();
  const Pose2 centre(t.x(), t.y(), 0.0);
  const double step = AngularSearchStep(lattice_.spacing(), points);
  const int half_count = static_cast<int>(std::ceil(M_PI / step));
  const Eigen::Array2i unbounded = Eigen::Array2i::Constant(kUnboundedOffset);
  return Search(DiscretizeScans(lattice_, centre, points, step, half_count, -unbounded, unbounded),
                centre, min_score);
}

template <class Lattice>
int FastCorrelativeScanMatcher<Lattice>::PeakCells() const {
  return OffsetsCovering(basis_, options_.peak_radius).maxCoeff();
}

template <class Lattice>
std::optional<CorrelativeMatch> FastCorrelativeScanMatcher<Lattice>::Search(
    std::vector<DiscreteScan> scans, const Pose2& centre, double min_score) const {
  if (grids_.cells().size().minCoeff() <= 0 || scans.empty() || scans.front().cells.empty()) {
    return std::nullopt;
  }
  ShrinkToFit(grids_.cells(), &scans);
  BranchAndBound search(grids_, scans);
  const Candidate best = search.Search(search.CoarsestCandidates(), grids_.max_depth(), min_score);
  if (best.scan < 0) return std::nullopt;
  CorrelativeMatch match;
  const Eigen::Vector2d t = centre.translation() + basis_ * best.offset.cast<double>().matrix();
  match.pose = Pose2(t.x(), t.y(), NormalizeAngle(scans[best.scan].theta));
  match.score = best.score;
  match.candidates = search.scored();
  if (options_.ambiguity_ratio > 0.0) {
    // The best pose outside this peak, if it comes within ambiguity_ratio of it.
    const double step = scans.size() > 1 ? std::abs(scans[1].theta - scans[0].theta) : M_PI;
    // Whole rotation steps, as far as peak_angle reaches (a hair over: the rotations' headings
    // differ by sums of `step`, rounded).
    const double angle = std::floor(options_.peak_angle / step) * step + kHeadingRounding;
    PeakZone peak{scans[best.scan].theta, best.offset, PeakCells(), angle};
    BranchAndBound runner_up(grids_, scans, &peak);
    // Not raised to min_score: a match just above it whose rival scores just below is no
    // less ambiguous. On the MIT Killian Court log, where it was, 64 of the 80 confirmed global
    // loop matches were wrong (mostly a corridor or a crossing seen turned by 90 or 180
    // degrees); without it 10 of 27.
    const double threshold = options_.ambiguity_ratio * best.score;
    const Candidate other =
        runner_up.Search(runner_up.CoarsestCandidates(), grids_.max_depth(), threshold);
    if (other.scan >= 0) {
      match.runner_up_score = other.score;
      const Eigen::Vector2d u = centre.translation() + basis_ * other.offset.cast<double>().matrix();
      match.runner_up_pose = Pose2(u.x(), u.y(), NormalizeAngle(scans[other.scan].theta));
    }
    match.candidates += runner_up.scored();
  }
  return match;
}

template std::vector<DiscreteScan> DiscretizeScans(const HexLattice&, const Pose2&,
                                                   const std::vector<Eigen::Vector2d>&, double,
                                                   int, const Eigen::Array2i&,
                                                   const Eigen::Array2i&);
template std::vector<DiscreteScan> DiscretizeScans(const SquareLattice&, const Pose2&,
                                                   const std::vector<Eigen::Vector2d>&, double,
                                                   int, const Eigen::Array2i&,
                                                   const Eigen::Array2i&);
template class FastCorrelativeScanMatcher<HexLattice>;
template class FastCorrelativeScanMatcher<SquareLattice>;

}  // namespace matching
}  // namespace hex_slam
