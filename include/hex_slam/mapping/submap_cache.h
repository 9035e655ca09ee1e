// The finished submaps the loop-closure worker has at hand: each one's map pyramid and its
// branch-and-bound grids (built on first use), least recently used dropped first once they take
// more than a memory budget. A dropped submap is drawn again from its nodes when it is needed.
#ifndef HEX_SLAM_MAPPING_SUBMAP_CACHE_H_
#define HEX_SLAM_MAPPING_SUBMAP_CACHE_H_

#include <algorithm>
#include <cstddef>
#include <list>
#include <memory>

#include "hex_slam/mapping/submap.h"
#include "hex_slam/matching/fast_correlative_scan_matcher.h"

namespace hex_slam {
namespace mapping {

template <class Lattice>
class SubmapCache {
 public:
  using Matcher = matching::FastCorrelativeScanMatcher<Lattice>;
  struct Entry {
    std::shared_ptr<const Submap<Lattice>> submap;
    // For local and for global searches; null until first needed.
    std::unique_ptr<const Matcher> matchers[2];
    std::size_t Bytes() const {
      std::size_t bytes = submap->maps().MemoryBytes();
      for (const auto& m : matchers) bytes += m ? m->MemoryBytes() : 0;
      return bytes;
    }
  };

  // Local searches run on pyramid level `local_level`, global ones on `global_level` (each the
  // coarsest if there are fewer).
  SubmapCache(std::size_t budget_bytes, const matching::FastCorrelativeScanMatcherOptions& matcher,
              int local_level, int global_level)
      : budget_bytes_(budget_bytes),
        matcher_options_(matcher),
        levels_{local_level, global_level} {}

  // The entry of submap `id`, now the most recently used; null if it is not held.
  Entry* Find(int id) {
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (it->submap->id() != id) continue;
      entries_.splice(entries_.begin(), entries_, it);
      return &entries_.front();
    }
    return nullptr;
  }

  // Holds `submap` (most recently used); may drop others to stay within the budget.
  Entry& Add(std::shared_ptr<const Submap<Lattice>> submap) {
    bytes_ += submap->maps().MemoryBytes();
    entries_.push_front({std::move(submap), nullptr});
    Trim();
    return entries_.front();
  }

  // The entry's branch-and-bound matcher for local or global searches, precomputed now if it
  // was not yet. `entry` must be the most recently used (as Find and Add leave it): it is never
  // the one dropped.
  const Matcher& MatcherOf(Entry* entry, bool global) {
    std::unique_ptr<const Matcher>& matcher = entry->matchers[global ? 1 : 0];
    if (!matcher) {
      const MapPyramid<Lattice>& maps = entry->submap->maps();
      matcher = std::make_unique<const Matcher>(
          maps.level(std::min(levels_[global ? 1 : 0], maps.size() - 1)), matcher_options_);
      bytes_ += matcher->MemoryBytes();
      ++matchers_built_;
      Trim();
    }
    return *matcher;
  }

  std::size_t bytes() const { return bytes_; }
  long matchers_built() const { return matchers_built_; }

 private:
  // The most recent entry stays even when it alone exceeds the budget: it is about to be used.
  void Trim() {
    while (entries_.size() > 1 && bytes_ > budget_bytes_) {
      bytes_ -= entries_.back().Bytes();
      entries_.pop_back();
    }
  }

  std::size_t budget_bytes_;
  matching::FastCorrelativeScanMatcherOptions matcher_options_;
  int levels_[2];
  std::list<Entry> entries_;  // most recently used first
  std::size_t bytes_ = 0;
  long matchers_built_ = 0;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_SUBMAP_CACHE_H_
