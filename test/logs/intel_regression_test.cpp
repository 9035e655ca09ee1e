// The whole Intel Research Lab subset (5505 scans, 1088 s) through the offline runner, on both
// lattices, with the odometry prior and without, and with hector's 0.025 m cells without it:
// every run must stay on track and score within bounds on the Freiburg relations. The goal is 0.05 m; hector_mapping with odometry scored
// 0.073 m here and the raw odometry 3.53 m. Skips without the data.
#include <string>

#include <gtest/gtest.h>

#include "hex_slam/logs/carmen_reader.h"
#include "hex_slam/logs/evaluation/map_consistency.h"
#include "hex_slam/logs/offline/offline_runner.h"
#include "hex_slam/logs/evaluation/relations.h"
#include "test_data.h"

namespace hex_slam {
namespace logs {
namespace {

struct IntelCase {
  const char* lattice;
  bool odometry;
  double resolution;
};

constexpr double kDefaultCell = 0.05;
constexpr double kHectorCell = 0.025;  // hector_mapping's default map_resolution

// The Intel log and its relations, read before each test (skipped when absent).
class IntelLogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string log_path = test::DataFile(test::kIntelLog);
    const std::string relations_path = test::DataFile(test::kIntelRelations);
    HEX_SLAM_REQUIRE_DATA(log_path);
    HEX_SLAM_REQUIRE_DATA(relations_path);
    ASSERT_EQ(ReadCarmenLog(log_path, CarmenReadOptions(), &log_), "");
    ASSERT_EQ(ReadRelations(relations_path, &relations_), "");
  }

  CarmenLog log_;
  std::vector<Relation> relations_;
};

class IntelRegressionTest : public IntelLogTest, public ::testing::WithParamInterface<IntelCase> {};

TEST_P(IntelRegressionTest, StaysOnTrackAndScoresWithinBounds) {

  SlamOptions options;
  options.lattice = GetParam().lattice;
  options.map_resolution = GetParam().resolution;
  // hector's cells need a fourth level on this 5 Hz log without odometry (below).
  if (GetParam().resolution == kHectorCell) options.map_min_coarse_resolution = 0.15;
  OfflineOptions run_options;
  run_options.use_odometry = GetParam().odometry;
  Slam slam(options);
  const OfflineRun run = RunOffline(log_.scans, run_options, &slam);
  EXPECT_EQ(run.count(ScanOutcome::kMatched), 5504);

  const RelationsReport r = EvaluateRelations(run.trajectory, relations_, RelationsOptions());
  ASSERT_EQ(r.evaluated, 1030);
  // Measured: 0.0148-0.0151 m at 0.05 m cells (hex 0.0148 / 0.0149 with / without odometry,
  // square 0.0151 both), 0.0158-0.0161 m at hector's; 0.22-0.25 deg.
  EXPECT_LT(r.translation.mean, 0.0225);
  EXPECT_LT(r.rotation.mean, 0.5);
  // Issue 13's goal for loop closure on this log, met with and without odometry.
  if (std::string(GetParam().lattice) == "hex" && GetParam().resolution == kDefaultCell) {
    EXPECT_LT(r.translation.mean, 0.015);
  }
  // Lost even once, the relations after it are off by metres. The worst one, measured
  // 0.09-0.16 m (0.19-0.59 m before the pose graph put slipped nodes back, stop 48), comes from
  // a turn on the spot early in the log (see docs/real_logs.md).
  EXPECT_LT(r.translation.p99, 0.15);
  EXPECT_LT(r.translation.max, 1.0);

  std::vector<Pose2> poses;
  for (const io::StampedPose& p : run.trajectory) poses.push_back(p.pose);
  SlamOptions metric = options;  // judged on one cell size, whatever the run's
  metric.map_resolution = kDefaultCell;
  const MapConsistencyReport consistency = EvaluateMapConsistency(log_.scans, poses, metric);
  EXPECT_GT(consistency.agreement.mean, 0.85);
  EXPECT_GT(consistency.low_quantile, 0.7);
  std::printf("intel %s %.3f m odometry %s: %.4f ± %.4f m, %.3f ± %.3f deg, p99 %.3f m, max %.3f m; "
              "agreement %.3f (p05 %.3f); %.3f ms/scan\n",
              GetParam().lattice, GetParam().resolution, GetParam().odometry ? "on" : "off",
              r.translation.mean,
              r.translation.stddev, r.rotation.mean, r.rotation.stddev, r.translation.p99,
              r.translation.max,
              consistency.agreement.mean, consistency.low_quantile,
              1e3 * run.processing_seconds / run.scan_ms.size());
}

INSTANTIATE_TEST_SUITE_P(
    AllSix, IntelRegressionTest,
    ::testing::Values(IntelCase{"hex", true, kDefaultCell}, IntelCase{"hex", false, kDefaultCell},
                      IntelCase{"square", true, kDefaultCell},
                      IntelCase{"square", false, kDefaultCell},
                      // hector's cells lost the log without odometry on three levels (1.1 m
                      // and 1.5 m); map_min_coarse_resolution 0.15 m adds the fourth.
                      IntelCase{"hex", false, kHectorCell}, IntelCase{"square", false, kHectorCell}),
    [](const ::testing::TestParamInfo<IntelCase>& info) {
      return std::string(info.param.lattice) +
             (info.param.resolution == kHectorCell ? "HectorCells" : "") +
             (info.param.odometry ? "WithOdometry" : "WithoutOdometry");
    });

// hector_mapping's own launch file (mapping_default.launch) sets map_update_angle_thresh 0.06 rad,
// so a user swapping hex_slam in gets that. With the single map and odometry the map then stopped
// being drawn at 245 s (a corridor whose walls ahead had been seen only at grazing angles: the
// score sank below tracking_ok_score 0.4 m after the last insertion, just before the next was
// due) and the run was lost for good, 5.86 m on the relations (10 of 10 nudged runs lost, 5.3-8.7
// m); SlamOptions::map_update_score_margin draws it before the score gets there.
TEST_F(IntelLogTest, WithHectorsLaunchFileThresholdsStaysOnTrack) {
  SlamOptions options;
  options.loop_closure.enabled = false;  // hector's single map
  options.map_update_distance_thresh = 0.4;
  options.map_update_angle_thresh = 0.06;
  Slam slam(options);
  const OfflineRun run = RunOffline(log_.scans, OfflineOptions(), &slam);
  EXPECT_EQ(run.times_lost, 0) << run.first_lost;
  const RelationsReport r = EvaluateRelations(run.trajectory, relations_, RelationsOptions());
  ASSERT_EQ(r.evaluated, 1030);
  // Measured 0.0154 m (the default thresholds: 0.0149 m).
  EXPECT_LT(r.translation.mean, 0.0225);
  EXPECT_LT(r.translation.max, 1.0);
  std::printf("intel with hector's launch-file thresholds: %.4f m, max %.3f m, %d map updates\n",
              r.translation.mean, r.translation.max, run.map_updates);
}

// The log subsampled in time (a scan at least `interval` s after the last kept) without
// odometry: at 1 Hz, steps of up to 0.84 m and turns of up to 1.1 rad between scans. Without the
// prediction-window search (SlamOptions::prediction_acc_lim_x) the 1 Hz estimate stayed behind
// while the robot drove off down the first corridor and ended 3.5 m (mean) from the full-rate run
// for the rest of the log, reported "ok"; at 2 Hz it was lost. Relations with both stamps kept
// are exact; the rest are read interpolated over the gaps (max_gap 1.5 s), which alone costs the
// full-rate trajectory, read at the same 1 Hz stamps, 0.067 m mean and 0.31 m at worst: a slide
// shows as metres. The front end on its own (loop closure off): with loop closure's submaps the
// 1 Hz run still slides (docs/real_logs.md).
struct SubsampledCase {
  double interval;  // s
  std::size_t scans;
  int exact_relations;
  double exact_mean;         // m, bound on the exact relations' mean
  int interpolated_relations;
  double interpolated_mean;  // m
  double interpolated_max;   // m
};

class IntelSubsampledTest : public IntelLogTest,
                            public ::testing::WithParamInterface<SubsampledCase> {};

TEST_P(IntelSubsampledTest, WithoutOdometryStaysTracked) {
  const SubsampledCase& c = GetParam();
  KeepScansApart(c.interval, &log_.scans);
  ASSERT_EQ(log_.scans.size(), c.scans);

  OfflineOptions run_options;
  run_options.use_odometry = false;
  SlamOptions options;
  options.loop_closure.enabled = false;
  Slam slam(options);
  const OfflineRun run = RunOffline(log_.scans, run_options, &slam);
  EXPECT_EQ(run.count(ScanOutcome::kMatched), static_cast<int>(c.scans) - 1);
  EXPECT_EQ(run.times_lost, 0);
  EXPECT_NE(slam.tracking_state(), TrackingState::kLost);

  const RelationsReport exact = EvaluateRelations(run.trajectory, relations_, RelationsOptions());
  ASSERT_EQ(exact.evaluated, c.exact_relations);
  EXPECT_LT(exact.translation.mean, c.exact_mean);
  RelationsOptions interpolated;
  interpolated.lookup.max_gap = 1.5;
  const RelationsReport r = EvaluateRelations(run.trajectory, relations_, interpolated);
  ASSERT_EQ(r.evaluated, c.interpolated_relations);
  EXPECT_LT(r.translation.mean, c.interpolated_mean);
  EXPECT_LT(r.translation.max, c.interpolated_max);
  std::printf("intel every %.1f s without odometry: exact %.4f m (%d relations); interpolated "
              "%.4f m, max %.3f m (%d); %d recoveries\n",
              c.interval, exact.translation.mean, exact.evaluated, r.translation.mean,
              r.translation.max, r.evaluated, run.recoveries);
}

// Measured: 1 Hz exact 0.0229 m, interpolated 0.0684 m mean, 0.627 m max (before: 3.5 m off);
// 2 Hz exact 0.0158 m, interpolated 0.0732 m, 0.355 m (before: lost).
INSTANTIATE_TEST_SUITE_P(
    OneAndTwoHertz, IntelSubsampledTest,
    ::testing::Values(SubsampledCase{1.0, 867, 50, 0.035, 773, 0.09, 0.95},
                      SubsampledCase{0.5, 1515, 100, 0.025, 1012, 0.09, 0.55}),
    [](const ::testing::TestParamInfo<SubsampledCase>& info) {
      return info.param.interval == 1.0 ? std::string("OneHertz") : std::string("TwoHertz");
    });

}  // namespace
}  // namespace logs
}  // namespace hex_slam
