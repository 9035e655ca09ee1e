// The front end's two overlapping submaps, as Cartographer's ActiveSubmaps2D: every inserted scan
// goes into both; a new submap is started when the newer one holds num_scans scans, and the older
// is finished at 2·num_scans and handed on. Scans are matched against the older (fuller) one, so
// the front end always has a map of at least num_scans scans around it, never an empty one.
// Only the older is filled on the scan path: the newer is filled on a thread of its own
// (SubmapFiller), waited for when it is first used as the older (matched against or inserted
// into), not when it becomes the older: between scans the filler has time to finish it, so the
// scan that finishes a submap does not wait for it. An inserted scan costs the scan path one
// submap's insertion, as the single map's.
//
// A new submap's storage is reserved at once for everything it will likely hold (its first
// position ± SubmapGridParameters::reserve_radius; beside an older submap, the older's box and
// the first scan's ± overlap_reserve_margin), and made resident at once (Paging::kAtAllocation):
// the submap seldom reallocates and copies its levels as it fills (growth stays the fallback for
// a robot that drives farther), and its cells, read by the matcher before they are written,
// fault once rather than twice. The storage is allocated by the submap's first insertion, so
// every submap but the very first gets it on the filler's thread, off the scan path.
//
// A robot that drives on (a corridor) outgrows that storage while the submap is the older, and
// each growth copies the submap's levels on the scan path (MIT CSAIL: 16 growths of 9-46 ms).
// So from the second half of its filling on, the filler also grows the newer submap to where
// the scans still to come into it will likely reach (Submap::CoverAhead). Only on its own
// thread, and only when it keeps up: a look-ahead the scan path did at its wait for the filler
// would be a growth copy on the scan path all the same, at the switch to the next submap (MIT
// CSAIL: one 12-17 ms wait a run). A robot that turns into new ground still grows the older
// submap on the scan path, as before. What the map reads does not depend on where its storage
// ends (the interpolations' edge paths), so neither does the trajectory.
#ifndef HEX_SLAM_MAPPING_ACTIVE_SUBMAPS_H_
#define HEX_SLAM_MAPPING_ACTIVE_SUBMAPS_H_

#include <memory>
#include <vector>

#include "hex_slam/mapping/submap.h"
#include "hex_slam/mapping/submap_filler.h"

namespace hex_slam {
namespace mapping {

// The newer submap's storage is grown ahead of the robot once it holds this fraction of its
// first num_scans scans (see the class comment): from then on the pace its sides have moved out
// at says where the scans to come will reach.
constexpr double kAheadFromFilled = 0.5;

template <class Lattice>
class ActiveSubmaps {
 public:
  using SubmapPtr = std::shared_ptr<Submap<Lattice>>;

  ActiveSubmaps(const SubmapOptions& options, const SubmapGridParameters& grid)
      : options_(options), grid_(grid) {}

  // Inserts a scan taken at `pose` (local frame) with its sensor at `origin` and its endpoints
  // `points` (local frame). Fills the submaps it went into, and returns the submap it finished
  // (null if none), which nothing here touches again: the caller may compact it.
  SubmapPtr Insert(const Pose2& pose, const Eigen::Vector2d& origin,
                   const std::vector<Eigen::Vector2d>& points,
                   std::vector<std::pair<int, Pose2>>* inserted_into) {
    WaitForMatchingSubmap();
    if (active_.empty() || scans_.back() >= options_.num_scans) {
      StartSubmap(pose, origin, points);
    }
    inserted_into->clear();
    for (std::size_t i = 0; i < active_.size(); ++i) {
      if (i == 0) {
        active_[i]->InsertScan(origin, points);
      } else {
        filler_->Push(active_[i], origin, points, ScansToCome(i));
      }
      ++scans_[i];
      inserted_into->emplace_back(active_[i]->id(), active_[i]->local_pose());
    }
    if (scans_.front() >= 2 * options_.num_scans) return FinishOldest();
    return nullptr;
  }

  // Finishes every active submap (the end of a trajectory), oldest first.
  std::vector<SubmapPtr> FinishAll() {
    std::vector<SubmapPtr> finished;
    while (!active_.empty()) finished.push_back(FinishOldest());
    return finished;
  }

  // The submap scans are matched against; null before the first insertion.
  const Submap<Lattice>* matching_submap() const {
    WaitForMatchingSubmap();
    return active_.empty() ? nullptr : active_.front().get();
  }
  int submaps_started() const { return next_id_; }
  // Returns once the filler's thread has done all it was given (SubmapFiller::WaitForThread).
  void WaitForFillerThread() const { filler_->WaitForThread(); }
  std::size_t MemoryBytes() const {
    filler_->WaitIdle();
    std::size_t bytes = 0;
    for (const SubmapPtr& s : active_) bytes += s->maps().MemoryBytes();
    return bytes;
  }

 private:
  void StartSubmap(const Pose2& pose, const Eigen::Vector2d& origin,
                   const std::vector<Eigen::Vector2d>& points) {
    const Pose2 frame(pose.x, pose.y, 0.0);
    Eigen::AlignedBox2d extent(origin);
    for (const Eigen::Vector2d& p : points) extent.extend(p);
    // Beside an older submap (complete: Insert waited for it), which has seen where the robot
    // has been lately, the new one mostly covers the same place. Alone, the first scan's box
    // grown by the distance the robot may travel while the submap fills: later scans see about
    // as far around their own positions.
    const Submap<Lattice>* older = active_.empty() ? nullptr : active_.front().get();
    extent = older ? OverlapReservedExtent(extent, older->extent(), origin, grid_)
                   : ReservedExtent(extent, origin, grid_);
    active_.push_back(std::make_shared<Submap<Lattice>>(next_id_++, frame, grid_, extent));
    scans_.push_back(0);
  }

  // How many scans active submap `i` (filled by the filler) will take after this one, for its
  // storage to be grown ahead of them: see the class comment. 0 before the second half of its
  // filling, while the pace its sides move out at says little yet.
  int ScansToCome(std::size_t i) const {
    const int scans = scans_[i];  // before this one
    if (scans < kAheadFromFilled * options_.num_scans) return 0;
    return 2 * options_.num_scans - 1 - scans;
  }

  // The filler's scans are in the older submap (from the switch on, the scan path fills it).
  void WaitForMatchingSubmap() const {
    if (!front_pending_) return;
    filler_->WaitIdle();
    front_pending_ = false;
  }

  SubmapPtr FinishOldest() {
    WaitForMatchingSubmap();  // (FinishAll) the oldest may have just become the older
    SubmapPtr oldest = active_.front();
    active_.erase(active_.begin());
    scans_.erase(scans_.begin());
    oldest->Finish();
    // The next one is matched against and filled on the scan path from now on, once the filler
    // has put in what it was given.
    front_pending_ = !active_.empty();
    return oldest;
  }

  SubmapOptions options_;
  SubmapGridParameters grid_;
  std::vector<SubmapPtr> active_;
  std::vector<int> scans_;  // scans given to each active submap (the filler's may not be in yet)
  // Behind a pointer so that the const MemoryBytes may wait for it.
  std::unique_ptr<SubmapFiller<Lattice>> filler_ = std::make_unique<SubmapFiller<Lattice>>();
  int next_id_ = 0;
  // The filler may still hold scans for the older submap (it became the older since the last
  // wait). Mutable: the const matching_submap waits for them.
  mutable bool front_pending_ = false;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_ACTIVE_SUBMAPS_H_
