#include "hex_slam/mapping/global_localizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <utility>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/scan_matcher.h"
#include "hex_slam/geometry/square_lattice.h"

namespace hex_slam {
namespace mapping {
namespace {

const char kMatcherPrefix[] = "loop_closure_";
const char kPrefix[] = "global_localization_";

// The map level and its search grids, built by the first search that needs them.
template <class Lattice>
class LatticeSearch {
 public:
  LatticeSearch(const GridMap<Lattice>& grid, const GlobalLocalizationOptions& options)
      : grid_(grid), options_(options) {}

  // The best pose of `points` anywhere on the map, above min_score.
  std::optional<matching::CorrelativeMatch> Run(const std::vector<Eigen::Vector2d>& points) {
    std::call_once(precomputed_, [this]() {
      matcher_ = std::make_unique<matching::FastCorrelativeScanMatcher<Lattice>>(
          grid_, options_.matcher);
    });
    std::vector<Eigen::Vector2d> searched;
    DecimateScan(points, options_.point_spacing, &searched);
    return matcher_->MatchFullSubmap(searched, options_.min_score);
  }

 private:
  const GridMap<Lattice> grid_;
  const GlobalLocalizationOptions options_;
  std::once_flag precomputed_;
  std::unique_ptr<matching::FastCorrelativeScanMatcher<Lattice>> matcher_;
};

}  // namespace

std::vector<std::string> GlobalLocalizationOptions::Validate() const {
  std::vector<std::string> errors;
  // The matcher's own checks, under this component's parameter names.
  for (std::string e : matcher.Validate()) {
    if (e.rfind(kMatcherPrefix, 0) == 0) e = kPrefix + e.substr(sizeof kMatcherPrefix - 1);
    errors.push_back(e);
  }
  if (search_level < 0) errors.push_back("global_localization_search_level must be >= 0");
  if (!(min_score >= 0.0 && min_score <= 1.0)) {
    errors.push_back("global_localization_min_score must lie in [0, 1]");
  }
  if (!(point_spacing >= 0.0 && std::isfinite(point_spacing))) {
    errors.push_back("global_localization_point_spacing must be finite and >= 0");
  }
  return errors;
}

template <class Lattice>
GlobalLocalizer::GlobalLocalizer(const GridMap<Lattice>& grid,
                                 const GlobalLocalizationOptions& options)
    : options_(options) {
  auto search = std::make_shared<LatticeSearch<Lattice>>(grid, options);
  search_ = [search](const std::vector<Eigen::Vector2d>& points) {
    GlobalSearchResult result;
    const auto start = std::chrono::steady_clock::now();
    result.match = search->Run(points);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
}

GlobalLocalizer::~GlobalLocalizer() { Wait(); }

bool GlobalLocalizer::Start(const std::vector<Eigen::Vector2d>& points, const Pose2& pose) {
  if (busy() || points.empty()) return false;
  if (!options_.background) {
    ready_ = search_(points);
    ready_->scan_pose = pose;
    return true;
  }
  // The thread gets its own copy of the scan; the search itself shares nothing mutable.
  running_ = std::async(std::launch::async, [search = search_, points, pose]() {
    GlobalSearchResult result = search(points);
    result.scan_pose = pose;
    return result;
  });
  return true;
}

std::optional<GlobalSearchResult> GlobalLocalizer::Poll() {
  if (running_.valid() &&
      running_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    ready_ = running_.get();
  }
  if (!ready_) return std::nullopt;
  std::optional<GlobalSearchResult> result = std::move(ready_);
  ready_.reset();
  ++stats_.searches;
  stats_.seconds += result->seconds;
  stats_.max_seconds = std::max(stats_.max_seconds, result->seconds);
  if (result->ambiguous()) ++stats_.ambiguous;
  else if (result->match) ++stats_.found;
  return result;
}

void GlobalLocalizer::Wait() {
  if (running_.valid()) running_.wait();
}

template GlobalLocalizer::GlobalLocalizer(const GridMap<HexLattice>&,
                                          const GlobalLocalizationOptions&);
template GlobalLocalizer::GlobalLocalizer(const GridMap<SquareLattice>&,
                                          const GlobalLocalizationOptions&);

}  // namespace mapping
}  // namespace hex_slam
