// A submap: the map pyramid of a run of consecutive scans, in the front end's (local) frame, as
// Cartographer's. Its frame for the pose graph is `local_pose` (the first scan's position, heading
// 0): a node matched at pose P on its grid lies at local_pose⁻¹·P in the submap's frame. Once
// finished it is frozen and shared, read-only, with the loop-closure worker, which may drop it
// and draw it again from its nodes (FromNodes) when it needs it back.
#ifndef HEX_SLAM_MAPPING_SUBMAP_H_
#define HEX_SLAM_MAPPING_SUBMAP_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/mapping/trajectory_node.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace mapping {

struct SubmapOptions {
  // Scans inserted into the newest submap before another is started; a submap is finished
  // after twice this many (Cartographer's num_range_data, 90 there, where every scan that moved
  // 0.2 m is inserted; here only those that moved map_update_distance_thresh).
  int num_scans = 45;
  // Consecutive endpoints a node keeps at least this many finest cells apart (0 keeps all).
  double node_point_spacing_cells = 0.5;

  std::vector<std::string> Validate() const;
};

// How a submap's grids are made: the front end's pyramid parameters.
struct SubmapGridParameters {
  double finest_spacing = 0.05;
  int levels = 3;
  OccupancyModel model;
  GridGrowthPolicy growth;
  // A new submap's storage covers its first scan's box grown by this (m) on every side: how far
  // the robot may travel while the submap fills. 0: the first scan's box only. Capped so a level
  // stays within a quarter of growth.max_cells.
  double reserve_radius = 0.0;
  // A submap started beside an older one covers its first scan's box and the older's box so
  // far grown by this (m) on every side instead (within the cap): consecutive submaps mostly
  // cover the same place, and storage no wider than needed touches fewer pages per written row.
  // < 0: reserve_radius, as for a submap started alone.
  double overlap_reserve_margin = -1.0;
};

// The side (m) of the largest square a level of a submap may cover: a quarter of
// growth.max_cells, so growing later still has room.
inline double SubmapCapSide(const SubmapGridParameters& grid) {
  // A square of side s holds about (s/d)² / (√3/2) hex cells (fewer square ones).
  constexpr double kHexCellsPerSquare = 2.0 / 1.7320508075688772;
  constexpr double kCapFraction = 0.25;
  return grid.finest_spacing *
         std::sqrt(kCapFraction * static_cast<double>(grid.growth.max_cells) / kHexCellsPerSquare);
}

// `box` cut to the cap's square around `centre` (a point of it): a scan that sees farther than a
// small map_max_cells allows keeps what lies near the robot instead of refusing the submap.
inline Eigen::AlignedBox2d CappedExtent(const Eigen::AlignedBox2d& box,
                                        const Eigen::Vector2d& centre,
                                        const SubmapGridParameters& grid) {
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(0.5 * SubmapCapSide(grid));
  return box.intersection(Eigen::AlignedBox2d(centre - half, centre + half));
}

// `box` (holding `centre`, the sensor) grown by reserve_radius on every side, but no larger than
// the cap.
inline Eigen::AlignedBox2d ReservedExtent(const Eigen::AlignedBox2d& box,
                                          const Eigen::Vector2d& centre,
                                          const SubmapGridParameters& grid) {
  const Eigen::AlignedBox2d capped = CappedExtent(box, centre, grid);
  const double r =
      std::min(grid.reserve_radius, 0.5 * (SubmapCapSide(grid) - capped.sizes().maxCoeff()));
  if (!(r > 0.0)) return capped;
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(r);
  return Eigen::AlignedBox2d(capped.min() - half, capped.max() + half);
}

// The storage of a submap started beside an older one whose box so far is `older`: see
// SubmapGridParameters::overlap_reserve_margin.
inline Eigen::AlignedBox2d OverlapReservedExtent(const Eigen::AlignedBox2d& box,
                                                 const Eigen::AlignedBox2d& older,
                                                 const Eigen::Vector2d& centre,
                                                 const SubmapGridParameters& grid) {
  if (grid.overlap_reserve_margin < 0.0 || older.isEmpty()) return ReservedExtent(box, centre, grid);
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(grid.overlap_reserve_margin);
  const Eigen::AlignedBox2d both = box.merged(older);
  return CappedExtent(Eigen::AlignedBox2d(both.min() - margin, both.max() + margin), centre, grid);
}

template <class Lattice>
class Submap {
 public:
  // `extent`: the initial storage (local frame), e.g. the first scan's bounding box; it grows as
  // later scans need (grid.growth). It is allocated by the first InsertScan, on whichever thread
  // makes it: the newer active submap's on the filler's, off the scan path. Until then the
  // storage covers the submap's origin alone.
  Submap(int id, const Pose2& local_pose, const SubmapGridParameters& grid,
         const Eigen::AlignedBox2d& extent)
      : id_(id),
        local_pose_(local_pose),
        maps_(grid.finest_spacing, grid.levels, grid.model, grid.growth,
              Eigen::AlignedBox2d(local_pose.translation())),
        reserve_(extent),
        grid_(grid) {}

  // A finished submap drawn again from the nodes that were inserted into it, in their order.
  static std::shared_ptr<const Submap> FromNodes(
      int id, const Pose2& local_pose, const SubmapGridParameters& grid,
      const std::vector<std::shared_ptr<const TrajectoryNode>>& nodes) {
    Eigen::AlignedBox2d extent(local_pose.translation());
    for (const auto& node : nodes) {
      extent.extend(node->local_pose * node->sensor_origin);
      for (const Eigen::Vector2d& p : node->points) extent.extend(node->local_pose * p);
    }
    // Drawn again, the submap's whole extent is known: storage sized to it at once never grows
    // (a growth copies every level, and its spare half stays held). The cap is for a box the
    // growth policy would refuse.
    GridIndex lo, hi;
    Lattice(grid.finest_spacing).IndexBounds(extent, &lo, &hi);
    if (static_cast<std::int64_t>(GridRect::FromCorners(lo, hi).size()) > grid.growth.max_cells) {
      extent = CappedExtent(extent, local_pose.translation(), grid);
    }
    auto submap = std::make_shared<Submap>(id, local_pose, grid, extent);
    std::vector<Eigen::Vector2d> points;
    for (const auto& node : nodes) {
      points.clear();
      for (const Eigen::Vector2d& p : node->points) points.push_back(node->local_pose * p);
      submap->InsertScan(node->local_pose * node->sensor_origin, points);
    }
    submap->Finish();
    submap->ShrinkToWritten();  // sized to its scans already: lets go of insertion's state
    return submap;
  }

  int id() const { return id_; }
  const Pose2& local_pose() const { return local_pose_; }
  const MapPyramid<Lattice>& maps() const { return maps_; }
  int num_scans() const { return num_scans_; }
  bool finished() const { return finished_; }

  // `origin` and `points` in the local frame. Ignored once finished.
  void InsertScan(const Eigen::Vector2d& origin, const std::vector<Eigen::Vector2d>& points) {
    if (finished_) return;
    if (!reserve_.isEmpty()) {
      maps_.Reserve(reserve_);
      reserve_.setEmpty();
    }
    maps_.InsertScan(origin, points);
    last_scan_.setEmpty();
    last_scan_.extend(origin);
    for (const Eigen::Vector2d& p : points) last_scan_.extend(p);
    extent_.extend(last_scan_);
    last_origin_ = origin;
    if (num_scans_ == 0) {
      first_scan_ = last_scan_;
      first_origin_ = origin;
    }
    ++num_scans_;
  }
  // Grows the storage now, as the growth policy would, to where `scans_to_come` more scans will
  // likely reach (AheadExtent): on the thread that calls this, rather than later in the
  // insertion that needs it. Not past the cap's area (SubmapCapSide), so a guess never takes
  // the room a scan's growth needs under growth.max_cells. Ignored once finished.
  void CoverAhead(int scans_to_come) {
    if (finished_ || num_scans_ < 2 || scans_to_come <= 0) return;
    const Eigen::AlignedBox2d ahead = AheadExtent(scans_to_come);
    const double cap_side = SubmapCapSide(grid_);
    if (maps_.level(0).StorageExtent().merged(ahead).volume() > cap_side * cap_side) return;
    maps_.EnsureCovers(ahead);
  }
  // The box of every sensor origin and endpoint inserted (local frame); empty before the first.
  const Eigen::AlignedBox2d& extent() const { return extent_; }
  void Finish() { finished_ = true; }
  // Once finished: each level's storage cut down to the cells its scans wrote (the rest reads
  // unknown, as before), since a finished submap never grows.
  void ShrinkToWritten() {
    if (finished_) maps_.ShrinkToWritten();
  }

 private:
  // Where `scans_to_come` more scans will likely reach, by two guesses that must agree (their
  // intersection; both hold the latest scan's box): the latest scan's box moved on as far as
  // the robot will go at its mean step so far, and the submap's box with each side moved on at
  // the mean pace per scan it has moved out at so far. In a corridor both push the far end; in
  // a room the second stops the first from reaching through the walls, and while the robot
  // turns on the spot the first stops the second from pushing every side out. Cut to the cap
  // around the latest sensor position.
  Eigen::AlignedBox2d AheadExtent(int scans_to_come) const {
    const double pace = static_cast<double>(scans_to_come) / (num_scans_ - 1);
    const Eigen::Vector2d ahead = pace * (last_origin_ - first_origin_);
    const Eigen::AlignedBox2d moved(last_scan_.min() + ahead, last_scan_.max() + ahead);
    const Eigen::AlignedBox2d pushed(extent_.min() - pace * (first_scan_.min() - extent_.min()),
                                     extent_.max() + pace * (extent_.max() - first_scan_.max()));
    return CappedExtent(last_scan_.merged(moved).intersection(pushed), last_origin_, grid_);
  }

  int id_;
  Pose2 local_pose_;
  MapPyramid<Lattice> maps_;
  Eigen::AlignedBox2d reserve_;  // storage still to allocate; empty once allocated
  Eigen::AlignedBox2d extent_;
  // For AheadExtent: the first and the latest scan's box (sensor and endpoints) and sensor.
  Eigen::AlignedBox2d first_scan_, last_scan_;
  Eigen::Vector2d first_origin_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_origin_ = Eigen::Vector2d::Zero();
  SubmapGridParameters grid_;  // for the cap of AheadExtent
  int num_scans_ = 0;
  bool finished_ = false;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_SUBMAP_H_
