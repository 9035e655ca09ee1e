// Planar poses to and from geometry_msgs, shared by every ROS program of the package (the node,
// the simulator, the bag writer), so a yaw becomes a quaternion in one place.
#ifndef HEX_SLAM_ROS_POSE_MSGS_H_
#define HEX_SLAM_ROS_POSE_MSGS_H_

#include <string>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {

// The yaw of a rotation: the heading of its image of the x axis. Unlike the z-y-x Euler yaw it
// stays right for a frame rolled by pi (a laser mounted upside down).
double YawOf(const geometry_msgs::Quaternion& q);
Pose2 PoseFromMsg(const geometry_msgs::Pose& pose);
Pose2 PoseFromTransform(const geometry_msgs::Transform& transform);

geometry_msgs::Quaternion QuaternionFromYaw(double yaw);
geometry_msgs::Pose ToPoseMsg(const Pose2& pose);
geometry_msgs::Transform ToTransformMsg(const Pose2& pose);
// `pose` is the child frame's pose in the parent frame.
geometry_msgs::TransformStamped ToTransformStampedMsg(const Pose2& pose, const ros::Time& stamp,
                                                      const std::string& parent,
                                                      const std::string& child);

}  // namespace hex_slam

#endif  // HEX_SLAM_ROS_POSE_MSGS_H_
