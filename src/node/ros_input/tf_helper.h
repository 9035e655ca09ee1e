// tf2 lookups the node needs, never throwing: the laser's mount at a scan's stamp (tf at that
// stamp, as hector_mapping's use_tf_scan_transformation: a moving or IMU-stabilised mount is
// followed scan by scan) and planar transforms at a stamp (odometry, initial poses).
//
// Waits are in wall-clock time. tf2's own timeouts run on ROS time, which under a simulator or
// a bag is the /clock: a simulator that waits for this node's pose before it advances the clock
// would then wait for a transform that waits for the clock.
#ifndef HEX_SLAM_NODE_ROS_INPUT_TF_HELPER_H_
#define HEX_SLAM_NODE_ROS_INPUT_TF_HELPER_H_

#include <optional>
#include <set>
#include <string>

#include <geometry_msgs/Transform.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <tf2_ros/buffer.h>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/sensor/sensor_mount.h"

namespace hex_slam {
namespace node {

// A laser's mount as tf gives it.
struct MountLookup {
  SensorMount mount;
  Pose2 planar;        // its position and yaw on the base, for the log
  double tilt = 0.0;   // rad between its scan plane and the base's x-y plane
  bool upside_down = false;
  bool latest = false;  // tf had nothing at the scan's stamp: the latest mount stands in
};

// The mount a 3D transform (the laser in the base frame) describes.
MountLookup MountFromTransform(const geometry_msgs::Transform& laser_in_base);

class TfHelper {
 public:
  TfHelper(const tf2_ros::Buffer* buffer, const std::string& base_frame)
      : buffer_(buffer), base_frame_(base_frame) {}

  // The mount of `laser_frame` on the base at `stamp`, waiting up to `wait` wall s for tf to reach
  // that stamp. When tf has only older (or static) transforms, the latest stands in with
  // `latest` set if the mount has not moved over tf's last second; a mount that moves is waited
  // for up to `max_wait` s in all, and nothing returned if it is still late. The first time a
  // frame is asked for, waits up to `max_wait` s for it to appear at all: a bag's /tf_static and
  // its first scan arrive together, and that scan should not be lost to the race. Nothing (and
  // a reason in `error`) if tf cannot place the frame.
  std::optional<MountLookup> Mount(const std::string& laser_frame, const ros::Time& stamp,
                                   double wait, double max_wait, std::string* error);

  // The pose of `source` in `target` at `stamp`, waiting up to `timeout` wall s for it.
  std::optional<Pose2> Lookup(const std::string& target, const std::string& source,
                              const ros::Time& stamp, double timeout, std::string* error) const;

  // Whether tf can relate the two frames at all (at their latest common time), without waiting.
  bool Connected(const std::string& target, const std::string& source) const;

 private:
  // The mount at `stamp` after waiting up to `wait` s; nothing with `error` empty when tf has
  // not reached the stamp, nothing with a reason when it cannot place the frame at all.
  std::optional<MountLookup> MountAtStamp(const std::string& laser_frame, const ros::Time& stamp,
                                          double wait, std::string* error) const;
  // Whether the mount `latest` gives differs from tf's one up to a second before it.
  bool MountMoved(const std::string& laser_frame,
                  const geometry_msgs::TransformStamped& latest) const;
  // Whether `source` can be placed in `target` at `stamp` within `wait` wall seconds.
  bool WaitFor(const std::string& target, const std::string& source, const ros::Time& stamp,
               double wait) const;

  const tf2_ros::Buffer* buffer_;
  std::string base_frame_;
  std::set<std::string> waited_for_;  // frames already given their one wait
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_ROS_INPUT_TF_HELPER_H_
