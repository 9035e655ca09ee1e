#include "ros_input/tf_helper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <Eigen/Geometry>
#include <tf2/exceptions.h>

#include "pose_msgs.h"

namespace hex_slam {
namespace node {
namespace {

bool Finite(const geometry_msgs::Transform& t) {
  for (double v : {t.translation.x, t.translation.y, t.translation.z, t.rotation.x, t.rotation.y,
                   t.rotation.z, t.rotation.w}) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// A transform with NaN or inf in it is as good as none: it would poison every later estimate.
geometry_msgs::Transform Checked(const geometry_msgs::TransformStamped& t) {
  if (!Finite(t.transform)) {
    throw tf2::InvalidArgumentException("tf holds a non-finite transform " + t.header.frame_id +
                                        "->" + t.child_frame_id);
  }
  return t.transform;
}

}  // namespace

MountLookup MountFromTransform(const geometry_msgs::Transform& laser_in_base) {
  const geometry_msgs::Quaternion& q = laser_in_base.rotation;
  Eigen::Quaterniond rotation(q.w, q.x, q.y, q.z);
  if (!(rotation.squaredNorm() > 0.0)) rotation = Eigen::Quaterniond::Identity();
  const Eigen::Matrix3d r = rotation.normalized().toRotationMatrix();
  const geometry_msgs::Vector3& t = laser_in_base.translation;
  MountLookup found;
  found.mount = SensorMount(r, Eigen::Vector3d(t.x, t.y, t.z));
  found.planar = PoseFromTransform(laser_in_base);
  found.upside_down = r(2, 2) < 0.0;
  found.tilt = std::acos(std::min(1.0, std::abs(r(2, 2))));
  return found;
}

std::optional<MountLookup> TfHelper::Mount(const std::string& laser_frame, const ros::Time& stamp,
                                           double wait, double first_wait, std::string* error) {
  if (laser_frame.empty()) {
    *error = "the scan has no frame_id";
    return std::nullopt;
  }
  if (waited_for_.insert(laser_frame).second) {
    WaitFor(base_frame_, laser_frame, ros::Time(0), first_wait);
  }
  WaitFor(base_frame_, laser_frame, stamp, wait);
  try {
    return MountFromTransform(Checked(buffer_->lookupTransform(base_frame_, laser_frame, stamp)));
  } catch (const tf2::ExtrapolationException&) {
    // Only older transforms (a mount published once, or slowly): the latest one stands in.
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
  try {
    MountLookup found = MountFromTransform(
        Checked(buffer_->lookupTransform(base_frame_, laser_frame, ros::Time(0))));
    found.latest = true;
    return found;
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
}

std::optional<Pose2> TfHelper::Lookup(const std::string& target, const std::string& source,
                                      const ros::Time& stamp, double timeout,
                                      std::string* error) const {
  WaitFor(target, source, stamp, timeout);
  try {
    return PoseFromTransform(Checked(buffer_->lookupTransform(target, source, stamp)));
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
}

bool TfHelper::WaitFor(const std::string& target, const std::string& source,
                       const ros::Time& stamp, double wait) const {
  // Transforms arrive on the listener's thread within a few ms of their stamp: a short poll
  // costs nothing next to the wait it bounds.
  constexpr auto kPoll = std::chrono::microseconds(500);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(std::max(0.0, wait));
  while (!buffer_->canTransform(target, source, stamp)) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(kPoll);
  }
  return true;
}

bool TfHelper::Connected(const std::string& target, const std::string& source) const {
  return buffer_->canTransform(target, source, ros::Time(0));
}

}  // namespace node
}  // namespace hex_slam
