// What the running process has used, for the tools' RESULT lines.
#ifndef HEX_SLAM_LOGS_OFFLINE_RESOURCE_USAGE_H_
#define HEX_SLAM_LOGS_OFFLINE_RESOURCE_USAGE_H_

namespace hex_slam {
namespace logs {

// The peak resident set size so far, in MiB (the process's own VmHWM); 0 if unavailable.
double PeakResidentMegabytes();

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_OFFLINE_RESOURCE_USAGE_H_
