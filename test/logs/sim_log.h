// A simulated log for the log tests: the room drive's scans as LogScans, with exact odometry,
// so runs can be checked against the truth.
#ifndef HEX_SLAM_TEST_LOGS_SIM_LOG_H_
#define HEX_SLAM_TEST_LOGS_SIM_LOG_H_

#include <random>
#include <vector>

#include "hex_slam/logs/log_scan.h"
#include "hex_slam/sim/room_drive.h"

namespace hex_slam {
namespace test {

inline std::vector<logs::LogScan> SimulatedLog(const sim::RoomDrive& drive, unsigned seed,
                                               std::size_t max_scans = 1u << 30) {
  std::mt19937_64 rng(seed);
  std::vector<logs::LogScan> scans;
  for (std::size_t i = 0; i < drive.truth.size() && i < max_scans; ++i) {
    logs::LogScan s;
    s.scan = sim::SimulateScan(drive.world, drive.truth[i], drive.lidar, 100.0 + drive.scan_period * i,
                               &rng);
    s.odometry = drive.truth[i];
    scans.push_back(std::move(s));
  }
  return scans;
}

}  // namespace test
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_LOGS_SIM_LOG_H_
