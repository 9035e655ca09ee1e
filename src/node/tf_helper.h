// tf2 lookups the node needs, never throwing: the laser's mount (looked up once per frame id and
// cached, since mounts do not move) and planar transforms at a stamp (odometry, initial poses).
#ifndef HEX_SLAM_NODE_TF_HELPER_H_
#define HEX_SLAM_NODE_TF_HELPER_H_

#include <map>
#include <optional>
#include <set>
#include <string>

#include <ros/time.h>
#include <tf2_ros/buffer.h>

#include "msg_conversion.h"

namespace hex_slam {
namespace node {

class TfHelper {
 public:
  TfHelper(const tf2_ros::Buffer* buffer, const std::string& base_frame)
      : buffer_(buffer), base_frame_(base_frame) {}

  // The mount of `laser_frame` on the base, from the latest transform tf has; nothing (and a
  // reason in `error`) if tf does not know it yet. The first time a frame is asked for, waits up
  // to `first_timeout` s: a bag's /tf_static and its first scan arrive together, and that scan
  // should not be lost to the race. Later calls for an unknown frame never wait: a scan callback
  // must not block again and again on a frame that may never appear.
  std::optional<LaserMount> Mount(const std::string& laser_frame, double first_timeout,
                                  std::string* error);

  // The pose of `source` in `target` at `stamp`, waiting up to `timeout` s for it to arrive.
  std::optional<Pose2> Lookup(const std::string& target, const std::string& source,
                              const ros::Time& stamp, double timeout, std::string* error) const;

  std::size_t cached_mounts() const { return mounts_.size(); }

 private:
  const tf2_ros::Buffer* buffer_;
  std::string base_frame_;
  std::map<std::string, LaserMount> mounts_;
  std::set<std::string> waited_for_;  // frames already given their one wait
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_TF_HELPER_H_
