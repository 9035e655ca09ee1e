// A world of line segments: exact ray casting, for tests whose ground truth must be exact.
#ifndef HEX_SLAM_SIM_SEGMENT_WORLD_H_
#define HEX_SLAM_SIM_SEGMENT_WORLD_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/world.h"

namespace hex_slam {
namespace sim {

class SegmentWorld : public World {
 public:
  void AddSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  // The closed outline of an axis-aligned rectangle.
  void AddRectangle(const Eigen::Vector2d& min, const Eigen::Vector2d& max);

  double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const override;

  // A copy with every segment moved by `placement` (rotate, then translate).
  SegmentWorld Transformed(const Pose2& placement) const;

  const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segments() const {
    return segments_;
  }

  // A 10 m × 8 m room with a dividing wall, pillars and boxes: corners and structure in every
  // direction so no pose is ambiguous. Origin (0, 0) is inside, near the middle.
  static SegmentWorld TestRoom();

 private:
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments_;
};

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_SEGMENT_WORLD_H_
