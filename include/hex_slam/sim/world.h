// A 2D world a simulated lidar can see: anything that answers "how far along this ray is the
// first obstacle".
#ifndef HEX_SLAM_SIM_WORLD_H_
#define HEX_SLAM_SIM_WORLD_H_

#include <Eigen/Core>

namespace hex_slam {
namespace sim {

class World {
 public:
  virtual ~World() = default;
  // Distance from `origin` along `angle` to the first obstacle, or +inf if none within
  // `max_range`.
  virtual double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const = 0;
};

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_WORLD_H_
