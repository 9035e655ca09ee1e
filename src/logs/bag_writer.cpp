#include "hex_slam/logs/bag_writer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include <boost/make_shared.hpp>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include "hex_slam/logs/stamp_order.h"
#include "pose_msgs.h"

namespace hex_slam {
namespace logs {
namespace {

// Lowered stamps keep this much (s) below their successor: tf2 drops a transform that repeats a
// stamp, and TUM files keep microseconds.
constexpr double kMinStampStep = 1e-6;

// Mountings closer than this (m, rad) are the same one.
constexpr double kSameMounting = 1e-9;

bool SamePose(const Pose2& a, const Pose2& b) {
  return std::abs(a.x - b.x) < kSameMounting && std::abs(a.y - b.y) < kSameMounting &&
         std::abs(NormalizeAngle(a.theta - b.theta)) < kSameMounting;
}

void WriteAll(const std::vector<LogScan>& scans, const std::vector<double>& stamps,
              const BagWriteOptions& options, rosbag::Bag* bag, BagWriteReport* report) {
  const ros::Time first(stamps.front());
  tf2_msgs::TFMessage mounting;
  mounting.transforms.push_back(
      ToTransformStampedMsg(scans.front().sensor_pose, first, options.base_frame, options.laser_frame));
  // rosbag play re-latches a topic whose connection header says so. A header given to write()
  // replaces the one rosbag would make, so it must name the type itself.
  auto latched = boost::make_shared<ros::M_string>();
  (*latched)["type"] = ros::message_traits::datatype(mounting);
  (*latched)["md5sum"] = ros::message_traits::md5sum(mounting);
  (*latched)["message_definition"] = ros::message_traits::definition(mounting);
  (*latched)["latching"] = "1";
  (*latched)["callerid"] = "/carmen_to_bag";
  bag->write("/tf_static", first, mounting, latched);

  for (std::size_t i = 0; i < scans.size(); ++i) {
    const LogScan& in = scans[i];
    const ros::Time stamp(stamps[i]);
    report->mounting_varies =
        report->mounting_varies || !SamePose(in.sensor_pose, scans.front().sensor_pose);
    if (in.odometry) {
      // Odometry first, so a consumer receiving the scan can already look it up.
      tf2_msgs::TFMessage tf;
      tf.transforms.push_back(ToTransformStampedMsg(*in.odometry, stamp, options.odom_frame, options.base_frame));
      bag->write("/tf", stamp, tf);
      nav_msgs::Odometry odom;
      odom.header.stamp = stamp;
      odom.header.frame_id = options.odom_frame;
      odom.child_frame_id = options.base_frame;
      odom.pose.pose.position.x = in.odometry->x;
      odom.pose.pose.position.y = in.odometry->y;
      odom.pose.pose.orientation = QuaternionFromYaw(in.odometry->theta);
      bag->write(options.odom_topic, stamp, odom);
      ++report->odometry;
    }
    sensor_msgs::LaserScan scan;
    scan.header.seq = static_cast<std::uint32_t>(i);
    scan.header.stamp = stamp;
    scan.header.frame_id = options.laser_frame;
    scan.angle_min = static_cast<float>(in.scan.angle_min);
    scan.angle_max = static_cast<float>(in.scan.angle_max);
    scan.angle_increment = static_cast<float>(in.scan.angle_increment);
    scan.range_min = static_cast<float>(in.scan.range_min);
    scan.range_max = static_cast<float>(in.scan.range_max);
    scan.ranges = in.scan.ranges;
    bag->write(options.scan_topic, stamp, scan);
    ++report->scans;
  }
}

}  // namespace

std::string WriteLogAsBag(const std::vector<LogScan>& scans, const std::string& path,
                          const BagWriteOptions& options, BagWriteReport* report) {
  *report = BagWriteReport();
  if (scans.empty()) return "no scans to write";
  std::vector<double> stamps;
  for (const LogScan& s : scans) stamps.push_back(s.scan.stamp);
  report->stamps_lowered = MakeStampsIncreasing(stamps, kMinStampStep, &stamps);
  if (stamps.front() <= 0.0 || stamps.back() >= static_cast<double>(UINT32_MAX)) {
    return "stamps outside ROS time's range (0, 2^32) s";
  }
  const std::string temporary = path + ".partial." + std::to_string(::getpid());
  try {
    rosbag::Bag bag;
    bag.open(temporary, rosbag::bagmode::Write);
    WriteAll(scans, stamps, options, &bag, report);
    bag.close();
  } catch (const std::exception& e) {
    std::remove(temporary.c_str());
    return "cannot write " + path + ": " + e.what();
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    return "cannot rename the finished bag to " + path;
  }
  return "";
}

}  // namespace logs
}  // namespace hex_slam
