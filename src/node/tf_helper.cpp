#include "tf_helper.h"

#include <tf2/exceptions.h>

namespace hex_slam {
namespace node {

std::optional<LaserMount> TfHelper::Mount(const std::string& laser_frame, double first_timeout,
                                          std::string* error) {
  const auto cached = mounts_.find(laser_frame);
  if (cached != mounts_.end()) return cached->second;
  if (laser_frame.empty()) {
    *error = "the scan has no frame_id";
    return std::nullopt;
  }
  const bool first = waited_for_.insert(laser_frame).second;
  try {
    const geometry_msgs::TransformStamped t = buffer_->lookupTransform(
        base_frame_, laser_frame, ros::Time(0), ros::Duration(first ? first_timeout : 0.0));
    const LaserMount mount = MountFromTransform(t.transform);
    mounts_.emplace(laser_frame, mount);
    return mount;
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
}

std::optional<Pose2> TfHelper::Lookup(const std::string& target, const std::string& source,
                                      const ros::Time& stamp, double timeout,
                                      std::string* error) const {
  try {
    const geometry_msgs::TransformStamped t =
        buffer_->lookupTransform(target, source, stamp, ros::Duration(timeout));
    return PoseFromTransform(t.transform);
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
}

}  // namespace node
}  // namespace hex_slam
