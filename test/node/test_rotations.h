// 3D rotations and transforms for the node's tests: elementary rotations and their messages.
#ifndef HEX_SLAM_TEST_NODE_TEST_ROTATIONS_H_
#define HEX_SLAM_TEST_NODE_TEST_ROTATIONS_H_

#include <Eigen/Geometry>
#include <geometry_msgs/Transform.h>

namespace hex_slam {
namespace testing_util {

inline geometry_msgs::Quaternion ToMsg(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  m.w = q.w();
  return m;
}

inline geometry_msgs::Transform MakeTransform(const Eigen::Vector3d& t,
                                              const Eigen::Quaterniond& q) {
  geometry_msgs::Transform m;
  m.translation.x = t.x();
  m.translation.y = t.y();
  m.translation.z = t.z();
  m.rotation = ToMsg(q);
  return m;
}

inline Eigen::Quaterniond About(const Eigen::Vector3d& axis, double angle) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
}
inline Eigen::Quaterniond Yaw(double a) { return About(Eigen::Vector3d::UnitZ(), a); }
inline Eigen::Quaterniond Roll(double a) { return About(Eigen::Vector3d::UnitX(), a); }
inline Eigen::Quaterniond Pitch(double a) { return About(Eigen::Vector3d::UnitY(), a); }

}  // namespace testing_util
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_NODE_TEST_ROTATIONS_H_
