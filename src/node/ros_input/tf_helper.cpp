#include "ros_input/tf_helper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
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

// A mount that moved less than this (m, rad) over the window is taken as fixed: a transform
// republished unchanged differs only by rounding.
constexpr double kMountMotionTolerance = 1e-6;
// How far back (s) tf's transforms are compared to see whether a mount moves.
constexpr double kMountMotionWindow = 1.0;

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
                                           double wait, double max_wait, std::string* error) {
  error->clear();
  if (laser_frame.empty()) {
    *error = "the scan has no frame_id";
    return std::nullopt;
  }
  if (waited_for_.insert(laser_frame).second) {
    WaitFor(base_frame_, laser_frame, ros::Time(0), max_wait);
  }
  if (std::optional<MountLookup> found = MountAtStamp(laser_frame, stamp, wait, error)) {
    return found;
  }
  if (!error->empty()) return std::nullopt;
  // tf has only older transforms: the latest stands in for a mount that does not move (one
  // published once, or slowly). One that moves (a pitching or stabilised bracket) would put the
  // scan's returns at the wrong heights and past the height filter (a busy machine's listener
  // can lag a scan by a few of its periods): it is waited for up to max_wait, as hector waits.
  geometry_msgs::TransformStamped latest;
  try {
    latest = buffer_->lookupTransform(base_frame_, laser_frame, ros::Time(0));
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
  if (MountMoved(laser_frame, latest)) {
    if (std::optional<MountLookup> found =
            MountAtStamp(laser_frame, stamp, std::max(0.0, max_wait - wait), error)) {
      return found;
    }
    if (error->empty()) {
      *error = "the mount moves and tf had not reached the scan's stamp after " +
               std::to_string(max_wait) + " s (tf_timeout): an older mount would misplace it";
    }
    return std::nullopt;
  }
  try {
    MountLookup found = MountFromTransform(Checked(latest));
    found.latest = true;
    return found;
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
}

std::optional<MountLookup> TfHelper::MountAtStamp(const std::string& laser_frame,
                                                  const ros::Time& stamp, double wait,
                                                  std::string* error) const {
  WaitFor(base_frame_, laser_frame, stamp, wait);
  try {
    return MountFromTransform(Checked(buffer_->lookupTransform(base_frame_, laser_frame, stamp)));
  } catch (const tf2::ExtrapolationException&) {
    return std::nullopt;  // not there yet: no error, the caller decides what stands in
  } catch (const tf2::TransformException& e) {
    *error = e.what();
    return std::nullopt;
  }
}

bool TfHelper::MountMoved(const std::string& laser_frame,
                          const geometry_msgs::TransformStamped& latest) const {
  // Static transforms carry stamp 0; a chain tf has seen for less than the window is compared
  // over what it has.
  const double span = std::min(kMountMotionWindow, latest.header.stamp.toSec());
  if (!(span > 0.0)) return false;
  geometry_msgs::TransformStamped earlier;
  try {
    earlier = buffer_->lookupTransform(base_frame_, laser_frame,
                                       latest.header.stamp - ros::Duration(span));
  } catch (const tf2::TransformException&) {
    return false;  // one transform so far: nothing to see it move by
  }
  const geometry_msgs::Vector3& a = latest.transform.translation;
  const geometry_msgs::Vector3& b = earlier.transform.translation;
  const geometry_msgs::Quaternion& p = latest.transform.rotation;
  const geometry_msgs::Quaternion& q = earlier.transform.rotation;
  const double moved = std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
  // 1 - |<p, q>| is about a quarter of the squared angle between the two rotations.
  const double turned = 2.0 * std::sqrt(std::max(
                                  0.0, 1.0 - std::abs(p.x * q.x + p.y * q.y + p.z * q.z + p.w * q.w)));
  return moved > kMountMotionTolerance || turned > kMountMotionTolerance;
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
