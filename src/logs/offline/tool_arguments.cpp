#include "hex_slam/logs/offline/tool_arguments.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace hex_slam {
namespace logs {

bool ParseNumber(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno != 0 || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

bool ParsePose(const std::string& text, Pose2* pose) {
  const std::size_t a = text.find(',');
  const std::size_t b = a == std::string::npos ? a : text.find(',', a + 1);
  if (b == std::string::npos || text.find(',', b + 1) != std::string::npos) return false;
  double x, y, yaw;
  if (!ParseNumber(text.substr(0, a), &x) || !ParseNumber(text.substr(a + 1, b - a - 1), &y) ||
      !ParseNumber(text.substr(b + 1), &yaw)) {
    return false;
  }
  *pose = Pose2(x, y, yaw);
  return true;
}

bool ParsePoint(const std::string& text, Eigen::Vector2d* point) {
  const std::size_t a = text.find(',');
  if (a == std::string::npos || text.find(',', a + 1) != std::string::npos) return false;
  double x, y;
  if (!ParseNumber(text.substr(0, a), &x) || !ParseNumber(text.substr(a + 1), &y)) return false;
  *point = Eigen::Vector2d(x, y);
  return true;
}

bool ParseSetting(const std::string& text, std::string* key, std::string* value) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) return false;
  *key = text.substr(0, eq);
  *value = text.substr(eq + 1);
  return true;
}

}  // namespace logs
}  // namespace hex_slam
