#include "hex_slam/logs/bag_messages.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include <ros/serialization.h>

#include "hex_slam/common/input_limits.h"

namespace hex_slam {
namespace logs {
namespace {

// Bytes of the fixed-size parts of the messages' wire format (ROS 1 serialization: little-endian,
// no padding; a string or an array is a uint32 count, then its elements).
constexpr std::uint64_t kStampBytes = 8;                // uint32 sec, uint32 nsec
constexpr std::uint64_t kScanFieldsBytes = 7 * 4;       // angle_min ... range_max, float32
constexpr std::uint64_t kTransformBytes = 7 * 8;        // Vector3 + Quaternion, float64
constexpr std::uint64_t kPoseBytes = 7 * 8;             // Point + Quaternion, float64
constexpr std::uint64_t kTwistBytes = 6 * 8;            // two Vector3
constexpr std::uint64_t kCovarianceBytes = 36 * 8;      // float64[36]
// tf2 refuses quaternions whose squared norm is further than this from 1; so do we.
constexpr double kQuaternionTolerance = 0.01;
// Scan geometry: angles within a turn, a range no 2D lidar comes near.
constexpr double kMaxScanAngle = 2.0 * M_PI + 1e-6;
constexpr double kMaxScanRange = 1e4;  // m
constexpr std::uint32_t kNanosecondsPerSecond = 1000000000u;

// Walks a message's bytes field by field, checking every length against what is left, before
// anything is allocated. The first problem is kept; later steps do nothing.
class WireWalk {
 public:
  WireWalk(const std::uint8_t* data, std::size_t size) : data_(data), left_(size) {}

  void Fixed(const std::string& field, std::uint64_t bytes) {
    if (!error_.empty()) return;
    if (bytes > left_) {
      error_ = field + " needs " + std::to_string(bytes) + " bytes, " + std::to_string(left_) +
               " are left (truncated or corrupt)";
      return;
    }
    data_ += bytes;
    left_ -= bytes;
  }
  // A uint32 count of elements of `element_bytes` each, at most `max_count` of them.
  void Array(const std::string& field, std::uint64_t element_bytes, std::uint64_t max_count) {
    const std::uint32_t count = Count(field);
    if (!error_.empty()) return;
    if (count > max_count) {
      error_ = field + " declares " + std::to_string(count) + " elements, more than " +
               std::to_string(max_count);
      return;
    }
    Fixed(field, element_bytes * count);
  }
  void String(const std::string& field) { Array(field, 1, kMaxBagMessageBytes); }
  void Header(const std::string& prefix) {
    Fixed(prefix + "header.seq", 4);
    Fixed(prefix + "header.stamp", kStampBytes);
    String(prefix + "header.frame_id");
  }
  bool ok() const { return error_.empty(); }
  // The walk's verdict: the first problem, or bytes left over past the last field.
  std::string Finish() const {
    if (!error_.empty() || left_ == 0) return error_;
    return std::to_string(left_) + " bytes past the message's last field (corrupt)";
  }
  // A uint32 length field.
  std::uint32_t Count(const std::string& field) {
    std::uint32_t count = 0;
    if (!error_.empty()) return 0;
    if (left_ < sizeof count) {
      error_ = field + ": its length is cut off (truncated or corrupt)";
      return 0;
    }
    std::memcpy(&count, data_, sizeof count);  // little-endian, as ROS 1 writes it
    data_ += sizeof count;
    left_ -= sizeof count;
    return count;
  }

 private:
  const std::uint8_t* data_;
  std::uint64_t left_;
  std::string error_;
};

// Deserializes bytes WireWalk has accepted.
template <class Msg>
std::string Deserialize(const std::uint8_t* data, std::size_t size, Msg* msg) {
  try {
    ros::serialization::IStream stream(const_cast<std::uint8_t*>(data),
                                       static_cast<std::uint32_t>(size));
    ros::serialization::deserialize(stream, *msg);
  } catch (const std::exception& e) {  // StreamOverrunException, bad_alloc
    return std::string("cannot deserialize: ") + e.what();
  }
  return "";
}

std::string SizeError(std::size_t size) {
  if (size <= kMaxBagMessageBytes) return "";
  return "the message is " + std::to_string(size) + " bytes, more than the " +
         std::to_string(kMaxBagMessageBytes) + " read";
}

std::string CheckStampField(const ros::Time& stamp, const std::string& field) {
  if (stamp.nsec < kNanosecondsPerSecond) return "";
  return field + ".nsec = " + std::to_string(stamp.nsec) + " is not below 10^9 (not a ROS time)";
}

std::string Number(const std::string& field, double value, double limit, const char* unit) {
  if (std::abs(value) <= limit) return "";
  std::ostringstream s;
  s << field << " = " << value;
  if (std::isfinite(value)) {
    s << " is beyond ±" << limit << " " << unit;
  } else {
    s << " is not a finite number";
  }
  return s.str();
}

std::string CheckPoint(const std::string& field, double x, double y, double z) {
  std::string error = Number(field + ".x", x, kMaxAbsCoordinate, "m");
  if (error.empty()) error = Number(field + ".y", y, kMaxAbsCoordinate, "m");
  if (error.empty()) error = Number(field + ".z", z, kMaxAbsCoordinate, "m");
  return error;
}

std::string CheckQuaternion(const std::string& field, const geometry_msgs::Quaternion& q) {
  const double norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  if (std::abs(norm2 - 1.0) <= kQuaternionTolerance) return "";
  std::ostringstream s;
  s << field << " (" << q.x << ", " << q.y << ", " << q.z << ", " << q.w << ") is not a unit "
    << "quaternion";
  return s.str();
}

std::string CheckScan(const sensor_msgs::LaserScan& msg) {
  std::string error = CheckStampField(msg.header.stamp, "header.stamp");
  const struct {
    const char* name;
    double value;
    double limit;
    const char* unit;
  } fields[] = {{"angle_min", msg.angle_min, kMaxScanAngle, "rad"},
                {"angle_max", msg.angle_max, kMaxScanAngle, "rad"},
                {"angle_increment", msg.angle_increment, kMaxScanAngle, "rad"},
                {"time_increment", msg.time_increment, kMaxRosTime, "s"},
                {"scan_time", msg.scan_time, kMaxRosTime, "s"},
                {"range_min", msg.range_min, kMaxScanRange, "m"},
                {"range_max", msg.range_max, kMaxScanRange, "m"}};
  for (const auto& f : fields) {
    if (error.empty()) error = Number(f.name, f.value, f.limit, f.unit);
  }
  // Range values themselves may be NaN or ±inf (REP 117): the scan sanitizer counts and drops
  // them, and those out of [range_min, range_max].
  return error;
}

}  // namespace

std::string CheckTransform(const geometry_msgs::TransformStamped& t) {
  const std::string name = "transform " + t.header.frame_id + " -> " + t.child_frame_id + ": ";
  std::string error = CheckStampField(t.header.stamp, "header.stamp");
  const geometry_msgs::Vector3& v = t.transform.translation;
  if (error.empty()) error = CheckPoint("translation", v.x, v.y, v.z);
  if (error.empty()) error = CheckQuaternion("rotation", t.transform.rotation);
  return error.empty() ? error : name + error;
}

std::string DecodeLaserScan(const std::uint8_t* data, std::size_t size,
                            sensor_msgs::LaserScan* msg) {
  std::string error = SizeError(size);
  if (!error.empty()) return error;
  WireWalk walk(data, size);
  walk.Header("");
  walk.Fixed("angle_min ... range_max", kScanFieldsBytes);
  walk.Array("ranges", sizeof(float), kMaxScanReadings);
  walk.Array("intensities", sizeof(float), kMaxScanReadings);
  error = walk.Finish();
  if (error.empty()) error = Deserialize(data, size, msg);
  return error.empty() ? CheckScan(*msg) : error;
}

std::string DecodeTfMessage(const std::uint8_t* data, std::size_t size, tf2_msgs::TFMessage* msg) {
  std::string error = SizeError(size);
  if (!error.empty()) return error;
  WireWalk walk(data, size);
  const std::uint32_t count = walk.Count("transforms");
  // Every transform takes bytes, so a corrupt count stops the walk when the data runs out.
  for (std::uint32_t i = 0; i < count && walk.ok(); ++i) {
    const std::string t = "transforms[" + std::to_string(i) + "].";
    walk.Header(t);
    walk.String(t + "child_frame_id");
    walk.Fixed(t + "transform", kTransformBytes);
  }
  error = walk.Finish();
  if (error.empty()) error = Deserialize(data, size, msg);
  for (std::size_t i = 0; error.empty() && i < msg->transforms.size(); ++i) {
    error = CheckTransform(msg->transforms[i]);
    if (!error.empty()) error = "transforms[" + std::to_string(i) + "] " + error;
  }
  return error;
}

std::string DecodeOdometry(const std::uint8_t* data, std::size_t size, nav_msgs::Odometry* msg) {
  std::string error = SizeError(size);
  if (!error.empty()) return error;
  WireWalk walk(data, size);
  walk.Header("");
  walk.String("child_frame_id");
  walk.Fixed("pose", kPoseBytes + kCovarianceBytes);
  walk.Fixed("twist", kTwistBytes + kCovarianceBytes);
  error = walk.Finish();
  if (error.empty()) error = Deserialize(data, size, msg);
  if (error.empty()) error = CheckStampField(msg->header.stamp, "header.stamp");
  const geometry_msgs::Point& p = msg->pose.pose.position;
  if (error.empty()) error = CheckPoint("pose.pose.position", p.x, p.y, p.z);
  if (error.empty()) error = CheckQuaternion("pose.pose.orientation", msg->pose.pose.orientation);
  return error;
}

}  // namespace logs
}  // namespace hex_slam
