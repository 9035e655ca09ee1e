// A world seen from another frame: the paper's "angle between the robot's first heading and the
// walls" is the whole map turned relative to the lattice, which rotating the frame does exactly
// (resampling a rotated image would not).
#ifndef HEX_SLAM_SIM_PLACED_WORLD_H_
#define HEX_SLAM_SIM_PLACED_WORLD_H_

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sim/world.h"

namespace hex_slam {
namespace sim {

class PlacedWorld : public World {
 public:
  // A point p of `base` sits at placement * p in this world. `base` must outlive this object.
  PlacedWorld(const World& base, const Pose2& placement)
      : base_(base), placement_(placement), inverse_(placement.inverse()) {}

  double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const override {
    return base_.CastRay(inverse_ * origin, angle - placement_.theta, max_range);
  }

  const Pose2& placement() const { return placement_; }

 private:
  const World& base_;
  Pose2 placement_;
  Pose2 inverse_;
};

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_PLACED_WORLD_H_
