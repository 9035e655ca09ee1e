// Decoding the messages hex_slam's offline tools read from bags (sensor_msgs/LaserScan,
// tf2_msgs/TFMessage, nav_msgs/Odometry), without trusting them. roscpp's deserializer sizes a
// vector from the length field in the data before it checks that the data holds that much: one
// corrupt LaserScan length of 3.4e9 allocates 13 GB before "Buffer Overrun". Here the message's
// own size is capped first, every length field is checked against the bytes that are left, and
// only then is the message deserialized; its values are then checked for what hex_slam uses
// (finite, within input_limits.h's bounds, stamps valid). Links roscpp's serialization only, so
// the fuzz target (test/fuzz) decodes exactly what the bag reader decodes.
#ifndef HEX_SLAM_LOGS_BAG_MESSAGES_H_
#define HEX_SLAM_LOGS_BAG_MESSAGES_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

namespace hex_slam {
namespace logs {

// The largest message read (bytes): a 65,536-beam scan with intensities is 0.5 MB, a tf message
// with a thousand transforms 0.1 MB.
constexpr std::size_t kMaxBagMessageBytes = std::size_t{16} << 20;

// Each returns an empty string, or what is wrong (a length that overruns the data, trailing
// bytes, a value out of bounds), naming the field. `msg` is only meaningful on success.
std::string DecodeLaserScan(const std::uint8_t* data, std::size_t size,
                            sensor_msgs::LaserScan* msg);
std::string DecodeTfMessage(const std::uint8_t* data, std::size_t size, tf2_msgs::TFMessage* msg);
std::string DecodeOdometry(const std::uint8_t* data, std::size_t size, nav_msgs::Odometry* msg);


// The value checks alone (DecodeTfMessage checks every transform with this).
std::string CheckTransform(const geometry_msgs::TransformStamped& t);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_BAG_MESSAGES_H_
