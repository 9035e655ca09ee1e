#include "hex_slam/logs/bag_reader.h"

#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/logs/bag_messages.h"
#include "hex_slam/logs/evaluation/trajectory_lookup.h"
#include "scan_msgs.h"  // the scan conversion shared with the node (hex_slam_ros)

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

// Topics of the bag with the given message type.
std::vector<std::string> TopicsOfType(const rosbag::Bag& bag, const std::string& type) {
  rosbag::View all(bag);
  std::set<std::string> topics;
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    if (c->datatype == type) topics.insert(c->topic);
  }
  return {topics.begin(), topics.end()};
}

// Reads and checks message `m` (bag_messages.h): its size is capped before anything is
// allocated. Returns an empty string or an error naming the message.
template <class Msg>
std::string ReadMessage(const rosbag::MessageInstance& m, int index,
                        std::string (*decode)(const std::uint8_t*, std::size_t, Msg*), Msg* msg) {
  const std::uint32_t size = m.size();
  std::string error;
  if (size > kMaxBagMessageBytes) {
    error = "declares " + std::to_string(size) + " bytes, more than the " +
            std::to_string(kMaxBagMessageBytes) + " read";
  } else {
    std::vector<std::uint8_t> bytes(size);
    ros::serialization::OStream out(bytes.data(), size);
    m.write(out);
    error = decode(bytes.data(), size, msg);
  }
  if (error.empty()) return "";
  std::ostringstream where;
  where << m.getTopic() << " message " << index << " (recorded at " << m.getTime() << " s): ";
  return where.str() + error;
}

// A message that failed its checks ends the read, unless the options say to skip it; then it is
// counted. Returns true when reading goes on.
bool SkipBadMessage(const std::string& error, const BagReadOptions& options, BagLog* log) {
  if (!options.skip_bad_messages) return false;
  if (log->bad_messages++ == 0) log->first_bad_message = error;
  return true;
}

// Loads every /tf and /tf_static message. Returns an empty string or the first bad message's
// error; `stored` counts the transforms stored.
std::string LoadTf(const rosbag::Bag& bag, const BagReadOptions& options, tf2::BufferCore* buffer,
                   BagLog* log, int* stored) {
  *stored = 0;
  int index = 0;
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{"/tf", "/tf_static"}));
  for (const rosbag::MessageInstance& m : view) {
    if (m.getDataType() != kTfMessageType) continue;
    tf2_msgs::TFMessage msg;
    const std::string error = ReadMessage(m, index++, &DecodeTfMessage, &msg);
    if (!error.empty()) {
      if (SkipBadMessage(error, options, log)) continue;
      return error;
    }
    const bool is_static = m.getTopic() == "/tf_static";
    for (geometry_msgs::TransformStamped t : msg.transforms) {
      t.header.frame_id = StripSlash(t.header.frame_id);
      t.child_frame_id = StripSlash(t.child_frame_id);
      // setTransform refuses (and logs) what it cannot store, such as a frame its own parent.
      if (buffer->setTransform(t, "bag", is_static)) ++*stored;
    }
  }
  return "";
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

std::string LoadOdometry(const rosbag::Bag& bag, const std::string& topic,
                         const BagReadOptions& options, BagLog* log,
                         std::vector<io::StampedPose>* poses) {
  int index = 0;
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  for (const rosbag::MessageInstance& m : view) {
    nav_msgs::Odometry msg;
    const std::string error = ReadMessage(m, index++, &DecodeOdometry, &msg);
    if (!error.empty()) {
      if (SkipBadMessage(error, options, log)) continue;
      return error;
    }
    const geometry_msgs::Pose& p = msg.pose.pose;
    poses->push_back(
        {msg.header.stamp.toSec(), Pose2(p.position.x, p.position.y, Yaw(p.orientation))});
  }
  return "";
}

// Where each scan's laser mounting and odometry come from.
struct ScanSources {
  const tf2::BufferCore* tf = nullptr;
  bool has_tf = false;
  bool odometry_from_tf = false;               // else from `odometry`, if any
  const TrajectoryLookup* odometry = nullptr;  // an Odometry topic's poses
  LookupOptions odometry_lookup;
};

// Empty when the bag has the scan topic; else the error, naming the LaserScan topics it has.
std::string CheckScanTopic(const rosbag::Bag& bag, const std::string& topic) {
  std::string known;
  for (const std::string& t : TopicsOfType(bag, kLaserScanType)) {
    if (t == topic) return "";
    known += " " + t;
  }
  return "no sensor_msgs/LaserScan topic " + topic +
         (known.empty() ? " (the bag has none)" : " (it has:" + known + ")");
}

// The laser in the base frame at `stamp`: given, or from tf. False when tf cannot say (the
// scan is dropped and counted); `error` names a mounting out of bounds.
bool SensorPose(const std::string& frame, const ros::Time& stamp, const BagReadOptions& options,
                const ScanSources& sources, BagLog* log, Pose2* pose, std::string* error) {
  if (options.sensor_pose) {
    *pose = *options.sensor_pose;
    return true;
  }
  if (!sources.has_tf || frame == options.base_frame) return true;  // identity
  try {
    *pose =
        ToPose(sources.tf->lookupTransform(options.base_frame, frame, stamp).transform);
  } catch (const tf2::TransformException& e) {
    if (log->dropped_no_transform++ == 0) {
      log->first_drop = "scan at " + std::to_string(stamp.toSec()) + " s: " + e.what();
    }
    return false;
  }
  *error = CheckSensorPose(*pose, "scan at " + std::to_string(stamp.toSec()) + " s: tf " +
                                      options.base_frame + " <- " + frame);
  return true;
}

std::optional<Pose2> OdometryAt(const ros::Time& stamp, const BagReadOptions& options,
                                const ScanSources& sources) {
  if (sources.odometry_from_tf) {
    try {
      return ToPose(
          sources.tf->lookupTransform(options.odom_frame, options.base_frame, stamp).transform);
    } catch (const tf2::TransformException&) {
      // Before the first odometry transform or past the last: matched without a prior.
      return std::nullopt;
    }
  }
  if (sources.odometry) return sources.odometry->At(stamp.toSec(), sources.odometry_lookup);
  return std::nullopt;
}

// Reads one scan message. Returns an error that stops the read; otherwise `scan` holds the scan,
// or nothing when it was dropped (counted in `log`).
std::string ReadScan(const rosbag::MessageInstance& m, const BagReadOptions& options,
                     const ScanSources& sources, BagLog* log, std::optional<LogScan>* scan) {
  scan->reset();
  sensor_msgs::LaserScan::Ptr msg(new sensor_msgs::LaserScan);
  std::string error = ReadMessage(m, log->scans_in_bag++, &DecodeLaserScan, msg.get());
  if (!error.empty()) return SkipBadMessage(error, options, log) ? "" : error;
  // A zero header stamp (some drivers) falls back to the time the bag recorded it.
  const ros::Time stamp = msg->header.stamp.isZero() ? m.getTime() : msg->header.stamp;
  LogScan read;
  read.scan = ScanFromMsg(*msg, stamp.toSec());
  if (!SensorPose(StripSlash(msg->header.frame_id), stamp, options, sources, log,
                  &read.sensor_pose, &error)) {
    return "";
  }
  if (!error.empty()) return SkipBadMessage(error, options, log) ? "" : error;
  read.odometry = OdometryAt(stamp, options, sources);
  if (options.read_odometry && log->odometry_source != "none" && !read.odometry) {
    ++log->scans_without_odometry;
  }
  *scan = std::move(read);
  return "";
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
    std::string error = CheckScanTopic(bag, options.scan_topic);
    if (!error.empty()) return path + ": " + error;
    rosbag::View whole(bag);
    const double span = (whole.getEndTime() - whole.getBeginTime()).toSec();
    tf2::BufferCore tf(ros::Duration(span + kTfCacheMargin));
    int transforms = 0;
    error = LoadTf(bag, options, &tf, log, &transforms);
    if (!error.empty()) return path + ": " + error;
    ScanSources sources;
    sources.tf = &tf;
    sources.has_tf = transforms > 0;
    std::string odometry_topic;
    error = PickOdometryTopic(bag, options, &odometry_topic);
    if (!error.empty()) return path + ": " + error;
    sources.odometry_from_tf = options.read_odometry && sources.has_tf &&
                               tf._frameExists(options.odom_frame) &&
                               tf._frameExists(options.base_frame);
    std::unique_ptr<TrajectoryLookup> odometry;
    if (!sources.odometry_from_tf && !odometry_topic.empty()) {
      std::vector<io::StampedPose> poses;
      error = LoadOdometry(bag, odometry_topic, options, log, &poses);
      if (!error.empty()) return path + ": " + error;
      odometry = std::make_unique<TrajectoryLookup>(std::move(poses));
      sources.odometry = odometry.get();
    }
    sources.odometry_lookup.max_gap = options.odometry_max_gap;
    log->mounting_source = options.sensor_pose ? "given"
                           : sources.has_tf    ? "tf " + options.base_frame + " <- scan frame"
                                               : "identity (the bag has no tf)";
    log->odometry_source = sources.odometry_from_tf
                               ? "tf " + options.odom_frame + " -> " + options.base_frame
                           : odometry ? "topic " + odometry_topic
                                      : "none";

    std::optional<LogScan> scan;
    for (const rosbag::MessageInstance& m :
         rosbag::View(bag, rosbag::TopicQuery(options.scan_topic))) {
      error = ReadScan(m, options, sources, log, &scan);
      if (!error.empty()) return path + ": " + error;
      if (scan) log->scans.push_back(std::move(*scan));
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
