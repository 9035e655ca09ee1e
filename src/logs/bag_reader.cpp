#include "hex_slam/logs/bag_reader.h"

#include <cmath>
#include <memory>
#include <set>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include "hex_slam/logs/trajectory_lookup.h"

namespace hex_slam {
namespace logs {
namespace {

constexpr const char* kLaserScanType = "sensor_msgs/LaserScan";
constexpr const char* kOdometryType = "nav_msgs/Odometry";
constexpr const char* kTfMessageType = "tf2_msgs/TFMessage";
// tf keeps the whole bag: the buffer's cache spans the bag plus this margin (s).
constexpr double kTfCacheMargin = 10.0;

// tf2 rejects frame ids with a leading slash, which ROS 1 bags often have ("/laser").
std::string StripSlash(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

// A bag records topics by their global names; a node's relative "scan" is "/scan" there.
std::string AbsoluteTopic(const std::string& topic) {
  return !topic.empty() && topic[0] != '/' ? "/" + topic : topic;
}

double Yaw(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

Pose2 ToPose(const geometry_msgs::Transform& t) {
  return Pose2(t.translation.x, t.translation.y, Yaw(t.rotation));
}

LaserScan ToScan(const sensor_msgs::LaserScan& msg, double stamp) {
  LaserScan scan;
  scan.stamp = stamp;
  scan.angle_min = msg.angle_min;
  scan.angle_max = msg.angle_max;
  scan.angle_increment = msg.angle_increment;
  scan.range_min = msg.range_min;
  scan.range_max = msg.range_max;
  scan.ranges = msg.ranges;
  return scan;
}

// Topics of the bag with the given message type.
std::vector<std::string> TopicsOfType(const rosbag::Bag& bag, const std::string& type) {
  rosbag::View all(bag);
  std::set<std::string> topics;
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    if (c->datatype == type) topics.insert(c->topic);
  }
  return {topics.begin(), topics.end()};
}

// Loads every /tf and /tf_static message. Returns the number of transforms stored.
int LoadTf(const rosbag::Bag& bag, tf2::BufferCore* buffer) {
  int stored = 0;
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& m : view) {
    if (m.getDataType() != kTfMessageType) continue;
    const tf2_msgs::TFMessage::ConstPtr msg = m.instantiate<tf2_msgs::TFMessage>();
    if (!msg) continue;
    const bool is_static = m.getTopic() == "/tf_static";
    for (geometry_msgs::TransformStamped t : msg->transforms) {
      t.header.frame_id = StripSlash(t.header.frame_id);
      t.child_frame_id = StripSlash(t.child_frame_id);
      // setTransform refuses (and logs) malformed transforms; they are simply not stored.
      if (buffer->setTransform(t, "bag", is_static)) ++stored;
    }
  }
  return stored;
}

std::string PickOdometryTopic(const rosbag::Bag& bag, const BagReadOptions& options,
                              std::string* topic) {
  topic->clear();
  if (!options.read_odometry) return "";
  const std::vector<std::string> odometry_topics = TopicsOfType(bag, kOdometryType);
  if (!options.odom_topic.empty()) {
    for (const std::string& t : odometry_topics) {
      if (t == options.odom_topic) *topic = t;
    }
    if (topic->empty()) return "no nav_msgs/Odometry topic " + options.odom_topic + " in the bag";
  } else if (odometry_topics.size() == 1) {
    *topic = odometry_topics.front();
  }
  return "";
}

std::vector<io::StampedPose> LoadOdometry(const rosbag::Bag& bag, const std::string& topic) {
  std::vector<io::StampedPose> poses;
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  for (const rosbag::MessageInstance& m : view) {
    const nav_msgs::Odometry::ConstPtr msg = m.instantiate<nav_msgs::Odometry>();
    if (!msg) continue;
    const geometry_msgs::Pose& p = msg->pose.pose;
    poses.push_back({msg->header.stamp.toSec(), Pose2(p.position.x, p.position.y, Yaw(p.orientation))});
  }
  return poses;
}

}  // namespace

std::string ReadBag(const std::string& path, const BagReadOptions& given, BagLog* log) {
  *log = BagLog();
  BagReadOptions options = given;
  options.scan_topic = AbsoluteTopic(options.scan_topic);
  if (!options.odom_topic.empty()) options.odom_topic = AbsoluteTopic(options.odom_topic);
  try {
    rosbag::Bag bag;
    bag.open(path, rosbag::bagmode::Read);
    bool scan_topic_found = false;
    for (const std::string& t : TopicsOfType(bag, kLaserScanType)) {
      scan_topic_found = scan_topic_found || t == options.scan_topic;
    }
    if (!scan_topic_found) {
      std::string known;
      for (const std::string& t : TopicsOfType(bag, kLaserScanType)) known += " " + t;
      return path + ": no sensor_msgs/LaserScan topic " + options.scan_topic +
             (known.empty() ? " (the bag has none)" : " (it has:" + known + ")");
    }
    rosbag::View whole(bag);
    const double span = (whole.getEndTime() - whole.getBeginTime()).toSec();
    tf2::BufferCore tf(ros::Duration(span + kTfCacheMargin));
    const bool has_tf = LoadTf(bag, &tf) > 0;
    std::string odometry_topic;
    std::string error = PickOdometryTopic(bag, options, &odometry_topic);
    if (!error.empty()) return path + ": " + error;
    const bool odometry_from_tf = options.read_odometry && has_tf &&
                                  tf._frameExists(options.odom_frame) &&
                                  tf._frameExists(options.base_frame);
    std::unique_ptr<TrajectoryLookup> odometry;
    if (!odometry_from_tf && !odometry_topic.empty()) {
      odometry = std::make_unique<TrajectoryLookup>(LoadOdometry(bag, odometry_topic));
    }
    log->mounting_source = options.sensor_pose ? "given"
                           : has_tf            ? "tf " + options.base_frame + " <- scan frame"
                                               : "identity (the bag has no tf)";
    log->odometry_source = odometry_from_tf ? "tf " + options.odom_frame + " -> " + options.base_frame
                           : odometry      ? "topic " + odometry_topic
                                           : "none";
    LookupOptions odometry_lookup;
    odometry_lookup.max_gap = options.odometry_max_gap;

    rosbag::View scans(bag, rosbag::TopicQuery(options.scan_topic));
    for (const rosbag::MessageInstance& m : scans) {
      const sensor_msgs::LaserScan::ConstPtr msg = m.instantiate<sensor_msgs::LaserScan>();
      if (!msg) continue;
      ++log->scans_in_bag;
      // A zero header stamp (some drivers) falls back to the time the bag recorded it.
      const ros::Time stamp = msg->header.stamp.isZero() ? m.getTime() : msg->header.stamp;
      LogScan scan;
      scan.scan = ToScan(*msg, stamp.toSec());
      const std::string frame = StripSlash(msg->header.frame_id);
      if (options.sensor_pose) {
        scan.sensor_pose = *options.sensor_pose;
      } else if (has_tf && frame != options.base_frame) {
        try {
          scan.sensor_pose = ToPose(tf.lookupTransform(options.base_frame, frame, stamp).transform);
        } catch (const tf2::TransformException& e) {
          if (log->dropped_no_transform++ == 0) {
            log->first_drop = "scan at " + std::to_string(stamp.toSec()) + " s: " + e.what();
          }
          continue;
        }
      }
      if (odometry_from_tf) {
        try {
          scan.odometry =
              ToPose(tf.lookupTransform(options.odom_frame, options.base_frame, stamp).transform);
        } catch (const tf2::TransformException&) {
          // Before the first odometry transform or past the last: matched without a prior.
        }
      }
      if (odometry) scan.odometry = odometry->At(scan.scan.stamp, odometry_lookup);
      if (options.read_odometry && log->odometry_source != "none" && !scan.odometry) {
        ++log->scans_without_odometry;
      }
      log->scans.push_back(std::move(scan));
    }
    bag.close();
  } catch (const rosbag::BagException& e) {
    return path + ": cannot read the bag: " + e.what();
  }
  if (log->scans.empty()) {
    return path + ": no usable scans on " + options.scan_topic +
           (log->first_drop.empty() ? std::string() : " (" + log->first_drop + ")");
  }
  return "";
}

}  // namespace logs
}  // namespace hex_slam
