#include "hex_slam/logs/resource_usage.h"

#include <sys/resource.h>

namespace hex_slam {
namespace logs {
namespace {

constexpr double kKibibytesPerMebibyte = 1024.0;

}  // namespace

double PeakResidentMegabytes() {
  struct rusage usage {};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return usage.ru_maxrss / kKibibytesPerMebibyte;  // Linux reports ru_maxrss in KiB
}

}  // namespace logs
}  // namespace hex_slam
