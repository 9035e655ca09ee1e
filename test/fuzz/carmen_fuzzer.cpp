// libFuzzer target: CARMEN log text, read as hex_slam_offline reads it, then the first scans run
// through the SLAM core on a small map (the values the reader lets through must be safe there).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "hex_slam/common/input_limits.h"
#include "hex_slam/logs/carmen_reader.h"
#include "hex_slam/logs/offline/offline_runner.h"

namespace {

constexpr std::size_t kScansThroughTheCore = 4;
constexpr int kSearchBudget = 500;
constexpr double kSearchWindow = 0.1;  // m and rad

hex_slam::SlamOptions SmallMap() {
  hex_slam::SlamOptions options;
  options.map_size = 32;
  options.map_max_cells = 1 << 14;  // growth stops early: each input stays cheap
  // A recovery search of the default budget takes ~0.1 s here and over 10 s (libFuzzer's
  // timeout) under the sanitizers on a loaded machine, and fuzzed stamps far apart make every
  // scan search its prediction window (prediction_acc_lim_x). Smaller windows and budget still
  // run every search (and refuse one over the budget, which is checked too) at ~10x the inputs.
  options.recovery.max_candidates = kSearchBudget;
  options.recovery.linear_window = kSearchWindow;
  options.recovery.angular_window = kSearchWindow;
  options.recovery_wide_linear_window = 2.0 * kSearchWindow;
  options.recovery_wide_angular_window = 2.0 * kSearchWindow;
  options.tracking.lost_search_linear_window = 2.0 * kSearchWindow;
  options.tracking.lost_search_max_candidates = kSearchBudget;
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hex_slam;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  logs::CarmenReadOptions options;
  options.skip_bad_lines = size % 2 == 1;  // both modes, from the same corpus
  logs::CarmenLog log;
  if (!logs::ParseCarmenLog(in, "fuzz", options, &log).empty()) return 0;
  HEX_SLAM_FUZZ_CHECK(!log.scans.empty());
  for (const logs::LogScan& s : log.scans) {
    HEX_SLAM_FUZZ_CHECK(!s.scan.ranges.empty());
    HEX_SLAM_FUZZ_CHECK(static_cast<long>(s.scan.ranges.size()) <= kMaxScanReadings);
    HEX_SLAM_FUZZ_CHECK(CheckStamp(s.scan.stamp, "").empty());
    HEX_SLAM_FUZZ_CHECK(CheckSensorPose(s.sensor_pose, "").empty());
    if (s.odometry) HEX_SLAM_FUZZ_CHECK(CheckPose(*s.odometry, "").empty());
  }
  if (log.scans.size() > kScansThroughTheCore) log.scans.resize(kScansThroughTheCore);
  Slam slam(SmallMap());
  const logs::OfflineRun run = logs::RunOffline(log.scans, logs::OfflineOptions(), &slam);
  for (const io::StampedPose& p : run.trajectory) HEX_SLAM_FUZZ_CHECK(IsFinite(p.pose));
  return 0;
}
