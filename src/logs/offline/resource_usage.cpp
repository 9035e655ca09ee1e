#include "hex_slam/logs/offline/resource_usage.h"

#include <sys/resource.h>

#include <fstream>
#include <string>

namespace hex_slam {
namespace logs {
namespace {

constexpr double kKibibytesPerMebibyte = 1024.0;

}  // namespace

double PeakResidentMegabytes() {
  // The process's own high-water mark. getrusage's ru_maxrss survives execve: a node started by
  // roslaunch would report the launcher's Python interpreter whenever that was larger.
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.compare(0, 6, "VmHWM:") == 0) return std::stod(line.substr(6)) / kKibibytesPerMebibyte;
  }
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return usage.ru_maxrss / kKibibytesPerMebibyte;  // Linux reports ru_maxrss in KiB
}

}  // namespace logs
}  // namespace hex_slam
