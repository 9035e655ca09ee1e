// The physical bounds that numbers from outside (log files, bags, command lines, messages) are
// checked against where they enter, so what passes is a plausible measurement rather than merely
// a finite double: a pose of 1e15 m or a stamp past 2106 is a corrupt field, and is refused with a
// message naming it instead of reaching the map.
#ifndef HEX_SLAM_COMMON_INPUT_LIMITS_H_
#define HEX_SLAM_COMMON_INPUT_LIMITS_H_

#include <string>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {

// m: a position in an odometry or log frame. Above the largest UTM northing (1e7 m), so
// georeferenced odometry passes.
constexpr double kMaxAbsCoordinate = 1e7;
// rad: a heading may be unwrapped over many turns (1e6 rad is 160,000 of them), not more.
constexpr double kMaxAbsAngle = 1e6;
// m: a laser farther than this from the robot's base is a calibration error. Its endpoints would
// lie that far from the base, and every rotation of the base would sweep them across the map.
constexpr double kMaxSensorOffset = 100.0;
// s: ROS 1 time is an unsigned 32-bit count of seconds, so stamps lie in [0, 2^32).
constexpr double kMaxRosTime = 4294967296.0;
// Readings in one scan: the densest 2D lidars give ~10^4 per revolution.
constexpr long kMaxScanReadings = 1 << 16;

// Each returns an empty string when the value is within bounds, else a message that begins with
// `what` ("--initial-pose", "ODOM pose", "/odom message 17 pose") and names the bad field.
std::string CheckPose(const Pose2& pose, const std::string& what);
std::string CheckSensorPose(const Pose2& pose, const std::string& what);
std::string CheckStamp(double stamp, const std::string& what);

bool IsFinite(const Pose2& pose);

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_INPUT_LIMITS_H_
