// Global localization on a fixed map (a saved map, update_map false): a scan searched by branch
// and bound (matching::FastCorrelativeScanMatcher) over the whole map at every heading, on a
// coarse pyramid level, accepted above a minimum score and only when no other place scores
// nearly as well. Slam then refines the pose with Gauss–Newton and takes it only when the
// tracking score backs it, as for the recovery search.
//
// The search grids are precomputed once per map (by the first search, on its thread), not per
// scan. A search over a building takes longer than a scan period, so by default it runs on a
// background thread: the scan path starts it with a copy of the scan and collects the result at
// a later scan, carrying the found pose over the front end's motion since the searched scan.
// One search runs at a time. With `background` false the search runs within the scan that
// starts it (results independent of timing: tests, reproducible offline runs).
//
// Not thread-safe by itself: Slam owns it and calls it from the scan path only.
#ifndef HEX_SLAM_MAPPING_GLOBAL_LOCALIZER_H_
#define HEX_SLAM_MAPPING_GLOBAL_LOCALIZER_H_

#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/matching/fast_correlative_scan_matcher.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace mapping {

struct GlobalLocalizationOptions {
  // Search the whole loaded map when the robot is lost on it, or when the first scans do not
  // confirm the pose it was given (or the origin, when none was given).
  bool enabled = true;
  // The pyramid level searched (0: finest; beyond the coarsest: the coarsest). Every heading
  // over the whole map: the default three levels' coarsest (4 times the finest spacing) keeps a
  // search within tens to hundreds of ms.
  int search_level = 2;
  // A search's best pose counts above this score (mean cell probability at the endpoints, as
  // loop_closure_global_min_score).
  double min_score = 0.6;
  // The searched scan keeps consecutive endpoints at least this far apart (m); Gauss–Newton
  // refines with all of them.
  double point_spacing = 0.1;
  // Run the search on a background thread (the scan path never waits for it); false: within the
  // scan that starts it.
  bool background = true;
  // The branch and bound's depth, the unknown cells' score and the ambiguity refusal
  // (ambiguity_ratio, peak_radius, peak_angle); the windows are unused (the whole map).
  matching::FastCorrelativeScanMatcherOptions matcher;

  // Empty when valid; otherwise one message per bad field, naming its parameter.
  std::vector<std::string> Validate() const;
};

struct GlobalSearchResult {
  // The best pose above min_score (in the map frame), if any; ambiguous when another place
  // scored nearly as well (then it must not be used).
  std::optional<matching::CorrelativeMatch> match;
  bool ambiguous() const { return match && match->runner_up_score > 0.0; }
  Pose2 scan_pose;  // the front end's estimate at the searched scan (Start's `pose`)
  double seconds = 0.0;  // the search's time (and the grids' precomputation, the first time)
};

struct GlobalLocalizationStats {
  int searches = 0;   // finished
  int found = 0;      // above min_score and unambiguous
  int ambiguous = 0;  // above min_score, but refused: another place scored nearly as well
  int accepted = 0;   // refined, backed by the tracking score, and taken by Slam
  double seconds = 0.0;       // all searches
  double max_seconds = 0.0;   // the longest search
};

class GlobalLocalizer {
 public:
  // Copies `grid` (the level to search): the map may be replaced while a search runs.
  template <class Lattice>
  GlobalLocalizer(const GridMap<Lattice>& grid, const GlobalLocalizationOptions& options);
  // Waits for a running search.
  ~GlobalLocalizer();
  GlobalLocalizer(const GlobalLocalizer&) = delete;
  GlobalLocalizer& operator=(const GlobalLocalizer&) = delete;

  // Starts a search for `points` (base frame) unless one is running or its result has not been
  // collected; `pose`: the front end's estimate at this scan. Returns whether it started.
  bool Start(const std::vector<Eigen::Vector2d>& points, const Pose2& pose);
  // The finished search's result, once; nothing while it runs or when none was started.
  std::optional<GlobalSearchResult> Poll();
  // Blocks until a running search has finished (its result then comes from Poll).
  void Wait();
  bool busy() const { return running_.valid() || ready_.has_value(); }

  GlobalLocalizationStats& stats() { return stats_; }
  const GlobalLocalizationStats& stats() const { return stats_; }

 private:
  using Search = std::function<GlobalSearchResult(const std::vector<Eigen::Vector2d>&)>;

  GlobalLocalizationOptions options_;
  Search search_;  // thread-safe: one search at a time; it precomputes the grids on first use
  std::future<GlobalSearchResult> running_;
  std::optional<GlobalSearchResult> ready_;
  GlobalLocalizationStats stats_;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_GLOBAL_LOCALIZER_H_
