#include "hex_slam/logs/evaluation/trajectory_lookup.h"

#include <algorithm>
#include <cmath>

#include "hex_slam/logs/evaluation/pose_interpolation.h"

namespace hex_slam {
namespace logs {

TrajectoryLookup::TrajectoryLookup(std::vector<io::StampedPose> poses) : poses_(std::move(poses)) {
  std::stable_sort(poses_.begin(), poses_.end(),
                   [](const io::StampedPose& a, const io::StampedPose& b) { return a.stamp < b.stamp; });
}

std::optional<Pose2> TrajectoryLookup::At(double stamp, const LookupOptions& options) const {
  if (poses_.empty()) return std::nullopt;
  // The first pose not before `stamp`, and the one before it.
  const auto after = std::lower_bound(
      poses_.begin(), poses_.end(), stamp,
      [](const io::StampedPose& p, double t) { return p.stamp < t; });
  const io::StampedPose* next = after != poses_.end() ? &*after : nullptr;
  const io::StampedPose* prev = after != poses_.begin() ? &*(after - 1) : nullptr;
  const io::StampedPose* nearest = next;
  if (prev && (!next || stamp - prev->stamp < next->stamp - stamp)) nearest = prev;
  if (std::abs(nearest->stamp - stamp) <= options.match_tolerance) return nearest->pose;
  if (!prev || !next || next->stamp - prev->stamp > options.max_gap) return std::nullopt;
  return InterpolatePose(prev->pose, next->pose,
                         (stamp - prev->stamp) / (next->stamp - prev->stamp));
}

}  // namespace logs
}  // namespace hex_slam
