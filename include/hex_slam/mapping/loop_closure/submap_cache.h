// What the loop-closure worker keeps at hand of the finished submaps, within a memory budget. A
// submap's map pyramid (what a match is refined on) and its branch-and-bound grids for local and
// for global searches (what a search runs on) are held and dropped each on its own, pyramids
// first: most searches find nothing to refine, and grids are a fraction of a pyramid (on the
// Freiburg hospital 0.6 MB for global searches, 2.2 MB for local ones, 20 MB a pyramid). Held
// and dropped whole, each pass of global searches over a large building drew most submaps again
// from their nodes: the hospital's 85 submaps were drawn 2481 times, now 36. A dropped pyramid
// is drawn again by the caller; dropped grids are precomputed again from the pyramid.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_SUBMAP_CACHE_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_SUBMAP_CACHE_H_

#include <algorithm>
#include <cstddef>
#include <iterator>
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

  // Local searches run on pyramid level `local_level`, global ones on `global_level` (each the
  // coarsest if there are fewer).
  SubmapCache(std::size_t budget_bytes, const matching::FastCorrelativeScanMatcherOptions& matcher,
              int local_level, int global_level)
      : budget_bytes_(budget_bytes),
        matcher_options_(matcher),
        levels_{local_level, global_level} {}

  // Submap `id`'s pyramid, now the most recently used; null if it is not held. The pointer stays
  // valid after the cache drops it.
  std::shared_ptr<const Submap<Lattice>> FindMaps(int id) {
    Item* item = Find(id, Part::kMaps);
    return item ? item->submap : nullptr;
  }

  // Holds `submap`'s pyramid (most recently used); may drop other parts to stay within the
  // budget.
  void AddMaps(std::shared_ptr<const Submap<Lattice>> submap) {
    const std::size_t bytes = submap->maps().MemoryBytes();
    const int id = submap->id();
    Add({id, Part::kMaps, bytes, std::move(submap), nullptr});
  }

  // Submap `id`'s grids for local or global searches, now the most recently used; null if they
  // are not held.
  std::shared_ptr<const Matcher> FindMatcher(int id, bool global) {
    Item* item = Find(id, global ? Part::kGlobalGrids : Part::kLocalGrids);
    return item ? item->matcher : nullptr;
  }

  // Precomputes `submap`'s grids for local or global searches and holds them (most recently
  // used).
  std::shared_ptr<const Matcher> AddMatcher(const Submap<Lattice>& submap, bool global) {
    const MapPyramid<Lattice>& maps = submap.maps();
    auto matcher = std::make_shared<const Matcher>(
        maps.level(std::min(levels_[global ? 1 : 0], maps.size() - 1)), matcher_options_);
    ++matchers_built_;
    Add({submap.id(), global ? Part::kGlobalGrids : Part::kLocalGrids, matcher->MemoryBytes(),
         nullptr, matcher});
    return matcher;
  }

  // Drops every part (their users keep theirs until they let go).
  void Clear() {
    items_.clear();
    bytes_ = 0;
  }

  std::size_t bytes() const { return bytes_; }
  long matchers_built() const { return matchers_built_; }

 private:
  enum class Part { kMaps, kLocalGrids, kGlobalGrids };
  struct Item {
    int id;
    Part part;
    std::size_t bytes;
    std::shared_ptr<const Submap<Lattice>> submap;  // kMaps
    std::shared_ptr<const Matcher> matcher;         // the grids
  };

  Item* Find(int id, Part part) {
    for (auto it = items_.begin(); it != items_.end(); ++it) {
      if (it->id != id || it->part != part) continue;
      items_.splice(items_.begin(), items_, it);
      return &items_.front();
    }
    return nullptr;
  }

  void Add(Item item) {
    bytes_ += item.bytes;
    items_.push_front(std::move(item));
    Trim();
  }

  // Over the budget, pyramids go first, least recently used first, then grids: a search needs
  // its grids, which are precomputed from the pyramid (drawn again if it was dropped), while a
  // pyramid is needed only to refine a match. The most recent item stays even when it alone
  // exceeds the budget: it is about to be used.
  void Trim() {
    while (items_.size() > 1 && bytes_ > budget_bytes_) {
      auto victim = std::prev(items_.end());
      for (auto it = victim; it != items_.begin(); --it) {
        if (it->part == Part::kMaps) {
          victim = it;
          break;
        }
      }
      bytes_ -= victim->bytes;
      items_.erase(victim);
    }
  }

  std::size_t budget_bytes_;
  matching::FastCorrelativeScanMatcherOptions matcher_options_;
  int levels_[2];
  std::list<Item> items_;  // most recently used first
  std::size_t bytes_ = 0;
  long matchers_built_ = 0;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_SUBMAP_CACHE_H_
