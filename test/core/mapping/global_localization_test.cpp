// Global localization on a loaded map (update_map false) against the simulator's truth: a start
// metres and tens of degrees off, or none at all, is found by the search over the whole map; a
// robot carried elsewhere is lost, then found; a map whose two halves look alike is refused
// rather than guessed.
#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "hex_slam/mapping/global_localizer.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/sim/segment_world.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace {

SlamOptions RoomOptions(const std::string& lattice) {
  SlamOptions o;
  o.lattice = lattice;
  o.map_resolution = 0.05;
  o.map_size = 256;
  return o;
}

double Distance(const Pose2& a, const Pose2& b) {
  return (a.translation() - b.translation()).norm();
}

// The room drive's scans, from `seed`.
class Scans {
 public:
  Scans(const sim::SegmentWorld& world, const sim::LidarModel& lidar, unsigned seed)
      : world_(world), lidar_(lidar), rng_(seed) {}
  LaserScan At(const Pose2& truth) {
    stamp_ += 0.1;
    return sim::SimulateScan(world_, truth, lidar_, stamp_, &rng_);
  }

 private:
  const sim::SegmentWorld& world_;
  const sim::LidarModel& lidar_;
  std::mt19937_64 rng_;
  double stamp_ = 0.0;
};

// A Slam mapping `truth` in `world`, its map then loaded into a localizing one.
class LoadedMap {
 public:
  LoadedMap(const sim::SegmentWorld& world, const sim::LidarModel& lidar,
            const std::vector<Pose2>& truth, const SlamOptions& options)
      : mapper_(options) {
    mapper_.Reset(truth.front());
    Scans scans(world, lidar, 5);
    for (const Pose2& pose : truth) mapper_.ProcessScan(scans.At(pose));
  }
  // A localizer on the map (update_map false), not yet placed.
  std::unique_ptr<Slam> Localizer(SlamOptions options) const {
    options.update_map = false;
    auto slam = std::make_unique<Slam>(options);
    if (slam->mutable_hex_maps()) *slam->mutable_hex_maps() = *mapper_.hex_maps();
    if (slam->mutable_square_maps()) *slam->mutable_square_maps() = *mapper_.square_maps();
    slam->UseLoadedMap();
    return slam;
  }

 private:
  Slam mapper_;
};

struct LocalizationRun {
  int ok_far = 0;           // scans reported ok while more than kFar off the truth
  int lost = 0;             // scans reported lost
  int found_at = -1;        // the scan whose whole-map search placed the robot
  int ok_at = -1;           // the first ok scan after found_at
  double final_error = 0.0;
  TrackingState first_state = TrackingState::kOk;  // after the first scan
  TrackingState final_state = TrackingState::kOk;
  std::vector<TrackingState> states;  // each change, in order
};

constexpr double kFar = 0.5;  // m: ok this far off would be a confident wrong pose

// Drives truth[first, first + count) through `slam`; with `wait`, each scan waits for a
// whole-map search it started, so the next collects it (the background path, deterministic).
LocalizationRun Localize(Slam* slam, Scans* scans, const std::vector<Pose2>& truth, int first,
                         int count, bool wait) {
  LocalizationRun run;
  for (int j = 0; j < count; ++j) {
    const Pose2& t = truth[first + j];
    const ScanReport r = slam->ProcessScan(scans->At(t));
    if (wait) slam->WaitForGlobalLocalization();
    const double error = Distance(r.pose, t);
    if (r.tracking_state == TrackingState::kOk && error > kFar) ++run.ok_far;
    if (r.tracking_state == TrackingState::kLost) ++run.lost;
    if (r.relocalized_globally && run.found_at < 0) run.found_at = j;
    if (r.tracking_state == TrackingState::kOk && run.found_at >= 0 && run.ok_at < 0) {
      run.ok_at = j;
    }
    if (r.tracking_changed) run.states.push_back(r.tracking_state);
    run.final_error = error;
    if (j == 0) run.first_state = r.tracking_state;
    run.final_state = r.tracking_state;
  }
  return run;
}

struct Case {
  std::string lattice;
  bool background;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.lattice << (c.background ? ", background" : ", in scan");
}

class GlobalLocalizationTest : public ::testing::TestWithParam<Case> {};
INSTANTIATE_TEST_SUITE_P(LatticesAndThreads, GlobalLocalizationTest,
                         ::testing::Values(Case{"hex", false}, Case{"hex", true},
                                           Case{"square", false}),
                         [](const auto& info) {
                           return info.param.lattice +
                                  (info.param.background ? "_background" : "_in_scan");
                         });

// The case: a saved map, the robot placed metres and tens of degrees off (3 m was out
// of the search while lost), or not placed at all (the origin). The whole-map search finds it:
// never ok while off, then ok within a few cm of the truth.
TEST_P(GlobalLocalizationTest, AFarOffOrMissingInitialPoseIsFoundOnTheWholeMap) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(360, 0.01);
  SlamOptions options = RoomOptions(GetParam().lattice);
  options.global_localization.background = GetParam().background;
  const LoadedMap map(drive.world, drive.lidar, drive.truth, options);
  const int start = 40;
  const Pose2& truth0 = drive.truth[start];
  struct Start {
    const char* name;
    std::optional<Pose2> offset;
  };
  for (const Start& s : {Start{"3 m off", Pose2(-3.0, 0.0, 0.0)},
                         Start{"3.2 m and 52 deg off", Pose2(2.0, -2.5, 0.9)},
                         Start{"turned round, 1 m off", Pose2(0.0, 1.0, 2.8)},
                         Start{"none given", std::nullopt}}) {
    SCOPED_TRACE(s.name);
    std::unique_ptr<Slam> slam = map.Localizer(options);
    if (s.offset) {
      ASSERT_TRUE(slam->SetPose(Pose2(truth0.x + s.offset->x, truth0.y + s.offset->y,
                                      truth0.theta + s.offset->theta)));
    }
    const double initial_error = Distance(slam->pose(), truth0);
    Scans scans(drive.world, drive.lidar, 7);
    const LocalizationRun run = Localize(slam.get(), &scans, drive.truth, start, 60,
                                         GetParam().background);
    const mapping::GlobalLocalizationStats stats = slam->global_localization_stats();
    EXPECT_EQ(run.ok_far, 0);
    EXPECT_EQ(run.final_state, TrackingState::kOk);
    EXPECT_LT(run.final_error, 0.03);
    EXPECT_GE(stats.accepted, 1);
    EXPECT_GE(run.found_at, 0);
    EXPECT_LE(run.found_at, 10);
    std::cout << GetParam().lattice << (GetParam().background ? " background" : " in scan")
              << ", " << s.name << " (" << initial_error << " m): found by scan " << run.found_at
              << ", ok at scan " << run.ok_at << ", lost for " << run.lost << " scans, final "
              << run.final_error << " m; " << stats.searches << " searches ("
              << stats.ambiguous << " ambiguous), longest " << stats.max_seconds * 1e3
              << " ms, mean " << stats.seconds / std::max(1, stats.searches) * 1e3 << " ms\n";
  }
}

// Tracking well, then carried to the far side of the room (the scans jump ahead along the
// drive): the matches fail, the state goes lost, and the whole-map search brings it back, ok.
TEST_P(GlobalLocalizationTest, AKidnappedRobotIsLostThenFound) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(360, 0.01);
  SlamOptions options = RoomOptions(GetParam().lattice);
  options.global_localization.background = GetParam().background;
  const LoadedMap map(drive.world, drive.lidar, drive.truth, options);
  std::unique_ptr<Slam> slam = map.Localizer(options);
  // Carried from the 30th scan after `start` to the farthest point of the drive.
  const int start = 20, count = 60;
  int there = start + 30;
  for (int i = there; i + count + 40 <= static_cast<int>(drive.truth.size()); ++i) {
    if (Distance(drive.truth[start + 29], drive.truth[i]) >
        Distance(drive.truth[start + 29], drive.truth[there])) {
      there = i;
    }
  }
  ASSERT_GT(Distance(drive.truth[start + 29], drive.truth[there]), 4.0);
  ASSERT_TRUE(slam->SetPose(drive.truth[start]));
  Scans scans(drive.world, drive.lidar, 9);
  const LocalizationRun before =
      Localize(slam.get(), &scans, drive.truth, start, 30, GetParam().background);
  ASSERT_EQ(before.final_state, TrackingState::kOk);
  ASSERT_LT(before.final_error, 0.03);
  const LocalizationRun after =
      Localize(slam.get(), &scans, drive.truth, there, count, GetParam().background);
  EXPECT_EQ(after.ok_far, 0);
  ASSERT_FALSE(after.states.empty());
  EXPECT_EQ(after.states.front(), TrackingState::kDegraded);
  EXPECT_GT(after.lost, 0);
  EXPECT_EQ(after.final_state, TrackingState::kOk);
  EXPECT_LT(after.final_error, 0.03);
  EXPECT_GE(after.found_at, 0);
  // Then an initialpose 3.2 m and 52° off while tracking ok: not ok until found again.
  const Pose2& here = drive.truth[there + count];
  ASSERT_TRUE(slam->SetPose(Pose2(here.x + 2.5, here.y - 2.0, here.theta + 0.9)));
  // The pose set from outside is unconfirmed: degraded until good matches and the search agree.
  EXPECT_EQ(slam->tracking_state(), TrackingState::kDegraded);
  const LocalizationRun placed =
      Localize(slam.get(), &scans, drive.truth, there + count, 40, GetParam().background);
  EXPECT_EQ(placed.ok_far, 0);
  EXPECT_NE(placed.first_state, TrackingState::kOk);
  EXPECT_EQ(placed.final_state, TrackingState::kOk);
  EXPECT_LT(placed.final_error, 0.03);
  EXPECT_GE(placed.found_at, 0);
  std::cout << GetParam().lattice << " kidnapped " << Distance(drive.truth[start + 29],
                                                               drive.truth[there])
            << " m: lost for " << after.lost << " scans, found by scan " << after.found_at
            << ", ok at " << after.ok_at << ", final " << after.final_error << " m; placed 3.2 m "
            << "off while ok: found by scan " << placed.found_at << ", ok at " << placed.ok_at
            << ", final " << placed.final_error << " m\n";
}

// A bare rectangular room looks the same from a pose and from its mirror through the room's
// centre: the whole-map search must refuse it (ambiguous), never relocalize to the wrong one
// and say ok.
TEST(GlobalLocalizationAmbiguityTest, ASymmetricRoomIsNotResolvedByGuessing) {
  const Pose2& placement = sim::GenericRoomPlacement();
  sim::SegmentWorld box;
  box.AddRectangle(Eigen::Vector2d(-4.0, -2.5), Eigen::Vector2d(4.0, 2.5));
  const sim::SegmentWorld world = box.Transformed(placement);
  sim::LidarModel lidar;
  lidar.beams = 360;
  lidar.field_of_view = 2.0 * M_PI;
  lidar.range_max = 12.0;
  lidar.range_noise_stddev = 0.01;
  // Mapped from a short turn near the centre.
  std::vector<Pose2> truth;
  for (int i = 0; i < 40; ++i) truth.push_back(placement * Pose2(-1.0 + 0.05 * i, 0.3, 0.02 * i));
  const SlamOptions options = RoomOptions("hex");
  const LoadedMap map(world, lidar, truth, options);

  // The robot at (2, 1) in the room; started at the centre, as far from it as from its mirror
  // (-2, -1) and beyond the search while lost (1 m) of both.
  const Pose2 robot = placement * Pose2(2.0, 1.0, 0.4);
  std::vector<Pose2> standing(60, robot);
  std::unique_ptr<Slam> slam = map.Localizer(options);
  ASSERT_TRUE(slam->SetPose(placement * Pose2(0.0, 0.0, 0.4)));
  Scans scans(world, lidar, 11);
  const LocalizationRun run = Localize(slam.get(), &scans, standing, 0, 60, false);
  const mapping::GlobalLocalizationStats stats = slam->global_localization_stats();
  EXPECT_EQ(run.ok_far, 0);
  EXPECT_GT(stats.searches, 0);
  EXPECT_EQ(stats.accepted, 0);
  EXPECT_EQ(stats.ambiguous, stats.searches);
  EXPECT_NE(run.final_state, TrackingState::kOk);
  std::cout << "symmetric room: " << stats.searches << " whole-map searches, "
            << stats.ambiguous << " refused as ambiguous, final state "
            << TrackingStateName(run.final_state) << ", " << run.final_error << " m off\n";
}

TEST(GlobalLocalizationOptionsTest, BadValuesAreNamed) {
  mapping::GlobalLocalizationOptions o;
  EXPECT_TRUE(o.Validate().empty());
  o.min_score = 1.5;
  o.matcher.branch_and_bound_depth = 0;
  const std::vector<std::string> errors = o.Validate();
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("global_localization_branch_and_bound_depth"), std::string::npos)
      << errors[0];
  EXPECT_NE(errors[1].find("global_localization_min_score"), std::string::npos) << errors[1];
}

}  // namespace
}  // namespace hex_slam
