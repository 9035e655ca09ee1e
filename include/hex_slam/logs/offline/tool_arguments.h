// Parsing the values of the tools' command-line options that CLI11 has no type for, or reads too
// leniently, strictly: the whole text must be the value, so "0.5m" or "1,2" for a number is an
// error rather than a silent 0.5 or 1 (src/tools/command_line.h).
#ifndef HEX_SLAM_LOGS_OFFLINE_TOOL_ARGUMENTS_H_
#define HEX_SLAM_LOGS_OFFLINE_TOOL_ARGUMENTS_H_

#include <string>

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace logs {

bool ParseNumber(const std::string& text, double* value);  // finite only
bool ParsePose(const std::string& text, Pose2* pose);      // "x,y,yaw"
bool ParsePoint(const std::string& text, Eigen::Vector2d* point);  // "x,y"
bool ParseSetting(const std::string& text, std::string* key, std::string* value);  // "key=value"

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_OFFLINE_TOOL_ARGUMENTS_H_
