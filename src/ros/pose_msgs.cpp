#include "pose_msgs.h"

#include <cmath>

namespace hex_slam {

double YawOf(const geometry_msgs::Quaternion& q) {
  // First column of the rotation matrix: where the x axis goes.
  const double r00 = 1.0 - 2.0 * (q.y * q.y + q.z * q.z);
  const double r10 = 2.0 * (q.x * q.y + q.w * q.z);
  return std::atan2(r10, r00);
}

Pose2 PoseFromMsg(const geometry_msgs::Pose& pose) {
  return Pose2(pose.position.x, pose.position.y, YawOf(pose.orientation));
}

Pose2 PoseFromTransform(const geometry_msgs::Transform& transform) {
  return Pose2(transform.translation.x, transform.translation.y, YawOf(transform.rotation));
}

geometry_msgs::Quaternion QuaternionFromYaw(double yaw) {
  geometry_msgs::Quaternion q;
  q.w = std::cos(0.5 * yaw);
  q.z = std::sin(0.5 * yaw);
  return q;
}

geometry_msgs::Pose ToPoseMsg(const Pose2& pose) {
  geometry_msgs::Pose msg;
  msg.position.x = pose.x;
  msg.position.y = pose.y;
  msg.orientation = QuaternionFromYaw(pose.theta);
  return msg;
}

geometry_msgs::Transform ToTransformMsg(const Pose2& pose) {
  geometry_msgs::Transform msg;
  msg.translation.x = pose.x;
  msg.translation.y = pose.y;
  msg.rotation = QuaternionFromYaw(pose.theta);
  return msg;
}

geometry_msgs::TransformStamped ToTransformStampedMsg(const Pose2& pose, const ros::Time& stamp,
                                                      const std::string& parent,
                                                      const std::string& child) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform = ToTransformMsg(pose);
  return t;
}

}  // namespace hex_slam
