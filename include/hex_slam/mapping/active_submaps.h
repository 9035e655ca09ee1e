// The front end's two overlapping submaps, as Cartographer's ActiveSubmaps2D: every inserted scan
// goes into both; a new submap is started when the newer one holds num_scans scans, and the older
// is finished at 2·num_scans and handed on. Scans are matched against the older (fuller) one, so
// the front end always has a map of at least num_scans scans around it, never an empty one.
//
// A new submap's storage (tens of MB for a building seen by a 30 m lidar) is allocated and
// cleared on another thread while the newer submap fills its second half, so starting a submap
// costs the scan path no more than inserting a scan.
#ifndef HEX_SLAM_MAPPING_ACTIVE_SUBMAPS_H_
#define HEX_SLAM_MAPPING_ACTIVE_SUBMAPS_H_

#include <future>
#include <memory>
#include <vector>

#include "hex_slam/mapping/submap.h"

namespace hex_slam {
namespace mapping {

template <class Lattice>
class ActiveSubmaps {
 public:
  using SubmapPtr = std::shared_ptr<Submap<Lattice>>;

  ActiveSubmaps(const SubmapOptions& options, const SubmapGridParameters& grid)
      : options_(options), grid_(grid) {}

  // Inserts a scan taken at `pose` (local frame) with its sensor at `origin` and its endpoints
  // `points` (local frame). Fills the submaps it went into, and returns the submap it finished
  // (null if none).
  std::shared_ptr<const Submap<Lattice>> Insert(const Pose2& pose, const Eigen::Vector2d& origin,
                                                const std::vector<Eigen::Vector2d>& points,
                                                std::vector<std::pair<int, Pose2>>* inserted_into) {
    if (active_.empty() || active_.back()->num_scans() >= options_.num_scans) {
      StartSubmap(pose, origin, points);
    }
    inserted_into->clear();
    for (const SubmapPtr& s : active_) {
      s->InsertScan(origin, points);
      inserted_into->emplace_back(s->id(), s->local_pose());
    }
    // Halfway through the newer submap, the next one's storage is prepared.
    if (!spare_.valid() && active_.back()->num_scans() >= options_.num_scans / 2) PrepareSpare();
    if (active_.front()->num_scans() >= 2 * options_.num_scans) return FinishOldest();
    return nullptr;
  }

  // Finishes every active submap (the end of a trajectory), oldest first.
  std::vector<std::shared_ptr<const Submap<Lattice>>> FinishAll() {
    std::vector<std::shared_ptr<const Submap<Lattice>>> finished;
    while (!active_.empty()) finished.push_back(FinishOldest());
    return finished;
  }

  // The submap scans are matched against; null before the first insertion.
  const Submap<Lattice>* matching_submap() const {
    return active_.empty() ? nullptr : active_.front().get();
  }
  const std::vector<SubmapPtr>& active() const { return active_; }
  int submaps_started() const { return next_id_; }
  std::size_t MemoryBytes() const {
    std::size_t bytes = 0;
    for (const SubmapPtr& s : active_) bytes += s->maps().MemoryBytes();
    return bytes;
  }

 private:
  // The newest submap's extent (the next scans will mostly see the same places): storage that
  // covers it spares most of the growths, each of which reallocates and copies every level.
  // (The older one's too would cover more than the next submap will see, and clearing the
  // larger storage costs more than the growths it saves.)
  Eigen::AlignedBox2d NewestExtent() const {
    return active_.empty() ? Eigen::AlignedBox2d() : active_.back()->extent();
  }

  void PrepareSpare() {
    const Eigen::AlignedBox2d extent = NewestExtent();
    const SubmapGridParameters grid = grid_;
    spare_ = std::async(std::launch::async, [grid, extent] {
      return std::make_unique<MapPyramid<Lattice>>(grid.finest_spacing, grid.levels, grid.model,
                                                    grid.growth, extent);
    });
  }

  void StartSubmap(const Pose2& pose, const Eigen::Vector2d& origin,
                   const std::vector<Eigen::Vector2d>& points) {
    const Pose2 frame(pose.x, pose.y, 0.0);
    if (spare_.valid()) {
      // The first scan grows it if it sees beyond what the newest submap covered.
      active_.push_back(
          std::make_shared<Submap<Lattice>>(next_id_++, frame, std::move(*spare_.get())));
      return;
    }
    Eigen::AlignedBox2d extent = NewestExtent();
    extent.extend(origin);
    for (const Eigen::Vector2d& p : points) extent.extend(p);
    active_.push_back(std::make_shared<Submap<Lattice>>(next_id_++, frame, grid_, extent));
  }

  std::shared_ptr<const Submap<Lattice>> FinishOldest() {
    SubmapPtr oldest = active_.front();
    active_.erase(active_.begin());
    oldest->Finish();
    return oldest;
  }

  SubmapOptions options_;
  SubmapGridParameters grid_;
  std::vector<SubmapPtr> active_;
  std::future<std::unique_ptr<MapPyramid<Lattice>>> spare_;  // the next submap's storage
  int next_id_ = 0;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_ACTIVE_SUBMAPS_H_
