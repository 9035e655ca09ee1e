#include "node_diagnostics.h"

#include <map>

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

std::map<std::string, std::string> Values(const diagnostic_msgs::DiagnosticStatus& status) {
  std::map<std::string, std::string> values;
  for (const auto& kv : status.values) values[kv.key] = kv.value;
  return values;
}

TEST(NodeDiagnosticsTest, ReportsCountersAndTimingAndWarnsOnlyWhileDropping) {
  ScanStats scans;
  scans.timing.Add(4.0, 3.5, 6.0);
  scans.drops.queue_overflow = 4;
  scans.drops.invalid = 2;
  scans.drops.no_laser_transform = 1;
  scans.time_jump_resets = 1;
  MapStats map;
  map.scans_processed = 10;
  map.memory_bytes = 3 * 1024 * 1024;
  const diagnostic_msgs::DiagnosticStatus dropping = MakeDiagnostics("n", scans, map, 0);
  EXPECT_EQ(dropping.level, diagnostic_msgs::DiagnosticStatus::WARN);
  const auto v = Values(dropping);
  EXPECT_EQ(v.at("scans_matched"), "1");
  EXPECT_EQ(v.at("scans_processed_by_core"), "10");
  EXPECT_EQ(v.at("dropped_invalid"), "2");
  EXPECT_EQ(v.at("dropped_no_laser_transform"), "1");
  EXPECT_EQ(v.at("dropped_queue_overflow"), "4");
  EXPECT_NEAR(std::stod(v.at("latency_p99_ms")), 6.0, 0.06);  // one sample: its 1 % bin
  EXPECT_EQ(v.at("latency_max_ms"), "6");
  EXPECT_EQ(v.at("time_jump_resets"), "1");
  EXPECT_EQ(v.at("callback_mean_ms"), "4");
  EXPECT_EQ(v.at("core_mean_ms"), "3.5");
  EXPECT_EQ(v.at("overhead_mean_ms"), "0.5");
  EXPECT_EQ(v.at("map_memory_mb"), "3");
  EXPECT_EQ(v.count("snapshot_ms"), 1u);
  EXPECT_EQ(v.count("raster_ms"), 1u);
  // No new drops since the last report: OK again.
  const diagnostic_msgs::DiagnosticStatus calm = MakeDiagnostics("n", scans, map, 7);
  EXPECT_EQ(calm.level, diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(calm.message, "mapping");
  map.paused = true;
  EXPECT_EQ(MakeDiagnostics("n", scans, map, 7).message, "paused");
}

TEST(NodeDiagnosticsTest, TheTrackingStateSetsTheLevelAndIsReported) {
  ScanStats scans;
  MapStats map;
  scans.tracking.state = "degraded";
  scans.tracking.reason = "a match scored 0.75, below tracking_ok_score 0.80";
  scans.tracking.match_score = 0.75;
  scans.tracking.times_lost = 2;
  scans.tracking.restarts = 1;
  diagnostic_msgs::DiagnosticStatus status = MakeDiagnostics("n", scans, map, 0);
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_EQ(status.message, "tracking degraded: " + scans.tracking.reason);
  auto v = Values(status);
  EXPECT_EQ(v.at("tracking_state"), "degraded");
  EXPECT_EQ(v.at("match_score"), "0.75");
  EXPECT_EQ(v.at("times_lost"), "2");
  EXPECT_EQ(v.at("restarts_after_lost"), "1");
  EXPECT_EQ(v.count("sigma_x_m"), 1u);
  scans.tracking.state = "lost";
  status = MakeDiagnostics("n", scans, map, 0);
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::ERROR);
  EXPECT_EQ(status.message.rfind("tracking lost: ", 0), 0u);
  scans.tracking.state = "ok";
  EXPECT_EQ(MakeDiagnostics("n", scans, map, 0).level, diagnostic_msgs::DiagnosticStatus::OK);
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
