// Slam's tracking state against the simulator's truth: blind scans, a localization started far
// off, a map that must not change while lost, the covariance along a corridor, a poisoned map.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "hex_slam/sim/building_loop.h"
#include "hex_slam/sim/lidar_model.h"
#include "hex_slam/sim/room_drive.h"
#include "hex_slam/sim/segment_world.h"
#include "hex_slam/common/input_limits.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace {

SlamOptions RoomOptions() {
  SlamOptions o;
  o.map_resolution = 0.05;
  o.map_size = 256;
  return o;
}

double Distance(const Pose2& a, const Pose2& b) {
  return (a.translation() - b.translation()).norm();
}

// A corridor 2 m wide along x from -5 to 60 m, closed at -5 m, with door frames (0.2 m deep)
// every 1.1-1.7 m along both walls: what there is to match along it.
sim::SegmentWorld CorridorWithDoorFrames() {
  sim::SegmentWorld corridor;
  corridor.AddSegment({-5.0, -1.0}, {60.0, -1.0});
  corridor.AddSegment({-5.0, 1.0}, {60.0, 1.0});
  corridor.AddSegment({-5.0, -1.0}, {-5.0, 1.0});
  for (double x = -4.0, gap = 1.1; x < 60.0; x += gap, gap = gap > 1.6 ? 1.1 : gap + 0.15) {
    corridor.AddSegment({x, -1.0}, {x, -0.8});
    corridor.AddSegment({x + 0.4, 1.0}, {x + 0.4, 0.8});
  }
  return corridor;
}

// A short-range lidar for CorridorWithDoorFrames: driving on 0.3 m a scan, it soon sees only
// what was never mapped.
sim::LidarModel FourMetreLidar() {
  sim::LidarModel lidar;
  lidar.range_max = 4.0;
  return lidar;
}

// An 8 x 5 m room with a pillar and a cabinet, both repeated turned by pi about the centre: a
// scan from (x, y, theta) is the scan from (-x, -y, theta + pi).
sim::SegmentWorld PointSymmetricRoom() {
  sim::SegmentWorld room;
  room.AddSegment({-4.0, -2.5}, {4.0, -2.5});
  room.AddSegment({4.0, -2.5}, {4.0, 2.5});
  room.AddSegment({4.0, 2.5}, {-4.0, 2.5});
  room.AddSegment({-4.0, 2.5}, {-4.0, -2.5});
  for (const double s : {1.0, -1.0}) {
    room.AddSegment({s * 1.8, s * 1.0}, {s * 2.1, s * 1.0});
    room.AddSegment({s * 2.1, s * 1.0}, {s * 2.1, s * 1.3});
    room.AddSegment({s * 2.1, s * 1.3}, {s * 1.8, s * 1.3});
    room.AddSegment({s * 1.8, s * 1.3}, {s * 1.8, s * 1.0});
    room.AddSegment({-s * 1.0, -s * 2.5}, {-s * 1.0, -s * 1.9});
    room.AddSegment({-s * 1.0, -s * 1.9}, {s * 0.2, -s * 1.9});
    room.AddSegment({s * 0.2, -s * 1.9}, {s * 0.2, -s * 2.5});
  }
  return room;
}

// The room drive without odometry, scan by scan; `blind` scans have no return at all.
class RoomRun {
 public:
  explicit RoomRun(const SlamOptions& options) : drive_(sim::MakeRoomDrive(360, 0.01)),
                                                 slam_(options), rng_(3) {
    slam_.Reset(drive_.truth.front());
  }
  ScanReport Scan(const Pose2& truth, bool blind = false) {
    LaserScan scan = sim::SimulateScan(drive_.world, truth, drive_.lidar, stamp_, &rng_);
    if (blind) {
      std::fill(scan.ranges.begin(), scan.ranges.end(), std::numeric_limits<float>::infinity());
    }
    stamp_ += drive_.scan_period;
    return slam_.ProcessScan(scan);
  }
  const sim::RoomDrive& drive() const { return drive_; }
  Slam& slam() { return slam_; }

 private:
  sim::RoomDrive drive_;
  Slam slam_;
  std::mt19937_64 rng_;
  double stamp_ = 0.0;
};

// The case: the robot drove, stopped, and its lidar saw nothing for 60 scans (6 s).
// Before: the last velocity carried the estimate on 1.82 m, and twenty good scans later it was
// still 1.81 m off, "matched". Now it moves at most over constant_velocity_horizon after the
// last match (one step here: 3.3 cm at 0.33 m/s), is lost after tracking_lost_after_scans, and
// the returning scans bring it back, ok, to the truth.
TEST(SlamTrackingTest, BlindScansDoNotPushTheEstimateAwayAndTrackingComesBack) {
  for (const bool moving_before : {false, true}) {
    SCOPED_TRACE(moving_before ? "moving until it went blind" : "standing still");
    RoomRun run(RoomOptions());
    const int stop = 150;
    for (int i = 0; i <= stop; ++i) run.Scan(run.drive().truth[i]);
    const Pose2 still = run.drive().truth[stop];
    if (!moving_before) {
      for (int i = 0; i < 20; ++i) run.Scan(still);
    }
    const double step = Distance(run.drive().truth[stop - 1], still);
    double worst = 0.0;
    bool degraded = false, lost = false;
    for (int i = 0; i < 60; ++i) {
      const ScanReport r = run.Scan(still, true);
      EXPECT_EQ(r.outcome, ScanOutcome::kTooFewPoints);
      EXPECT_FALSE(r.pose_from_scan);
      EXPECT_EQ(r.covariance, UnknownPoseCovariance());
      worst = std::max(worst, Distance(r.pose, still));
      degraded |= r.tracking_state == TrackingState::kDegraded;
      lost |= r.tracking_state == TrackingState::kLost;
    }
    EXPECT_TRUE(degraded);
    EXPECT_TRUE(lost);
    // Horizon 0.2 s at 10 Hz: the scan after the match and one more are extrapolated.
    EXPECT_LT(worst, 2.0 * step + 0.01);
    ScanReport r;
    for (int i = 0; i < 20; ++i) r = run.Scan(still);
    EXPECT_EQ(r.tracking_state, TrackingState::kOk);
    EXPECT_LT(Distance(r.pose, still), 0.01);
    EXPECT_LT(std::sqrt(r.covariance(0, 0)), 0.01);
    std::cout << (moving_before ? "moving" : "standing") << ": worst while blind " << worst
              << " m, after 20 good scans " << Distance(r.pose, still) << " m\n";
  }
}

// hector's mapping_default.launch: 5 cm cells on two levels leave a 0.1 m coarsest cell, where
// the search while lost (±1 m, every heading) took more poses than its budget even in the
// narrowest of its heading sectors, with a 30 m lidar down a corridor, and was refused at every
// scan: a robot lost there never searched again (the Intel subset without odometry, lost at
// scan 1219, stayed lost for 3776 scans). Here the robot drives the building's corridor, goes
// blind until lost, and sees again from further along; on either pyramid it must find itself
// there without a search refused.
TEST(SlamTrackingTest, LostOnHectorsTwoLevelsSearchesAndFindsItself) {
  static const sim::BuildingLoop building = sim::MakeBuildingLoop(1);
  for (const int levels : {3, 2}) {
    SCOPED_TRACE(std::to_string(levels) + " levels");
    SlamOptions options;
    options.map_resolution = 0.05;
    options.map_size = 512;
    options.map_multi_res_levels = levels;
    options.loop_closure.enabled = false;
    Slam slam(options);
    slam.Reset(building.truth.front());
    std::mt19937_64 rng(2);
    double stamp = 0.0;
    const auto scan_from = [&](const Pose2& truth, bool blind) {
      LaserScan scan = sim::SimulateScan(building.world, truth, building.lidar, stamp, &rng);
      if (blind) {
        std::fill(scan.ranges.begin(), scan.ranges.end(), std::numeric_limits<float>::infinity());
      }
      stamp += building.scan_period;
      return slam.ProcessScan(scan);
    };
    const int stop = 120;
    for (int i = 0; i <= stop; ++i) scan_from(building.truth[i], false);
    const Pose2 still = building.truth[stop];
    bool lost = false;
    for (int i = 0; i < 30; ++i) {
      lost |= scan_from(still, true).tracking_state == TrackingState::kLost;
    }
    ASSERT_TRUE(lost);
    int further = stop;
    while (Distance(building.truth[further], still) < 0.6) ++further;
    const Pose2 seen_from = building.truth[further];
    ASSERT_LT(Distance(seen_from, still), 0.9) << "within the search's 1 m";
    ScanReport r;
    bool refused = false;
    for (int i = 0; i < 80; ++i) {
      r = scan_from(seen_from, false);
      refused |= r.message.find("refused") != std::string::npos;
      if (r.tracking_state == TrackingState::kOk) break;
    }
    EXPECT_FALSE(refused) << r.message;
    EXPECT_EQ(r.tracking_state, TrackingState::kOk);
    EXPECT_LT(Distance(r.pose, seen_from), 0.05);
  }
}

// Localization on a saved map, started far off: the oracle is the simulator's truth. The state
// may be degraded or lost while the estimate is off, never ok more than 0.5 m from the truth.
// The search while lost (1 m, every heading) finds the robot 46° off, and 46° and 1.8 m off; 3 m
// off is out of its reach: lost it stays, and says so. (The search over the whole map, off here,
// finds it: global_localization_test.cpp.)
TEST(SlamTrackingTest, LocalizationStartedFarOffIsNeverOkWhileOffAndFindsItself) {
  const sim::RoomDrive drive = sim::MakeRoomDrive(360, 0.01);
  Slam mapper(RoomOptions());
  mapper.Reset(drive.truth.front());
  std::mt19937_64 rng(5);
  for (std::size_t i = 0; i < drive.truth.size(); ++i) {
    mapper.ProcessScan(sim::SimulateScan(drive.world, drive.truth[i], drive.lidar, 0.1 * i, &rng));
  }
  SlamOptions options = RoomOptions();
  options.update_map = false;
  options.global_localization.enabled = false;
  const int start = 40;
  for (const Pose2& offset : {Pose2(0.0, 0.0, 0.8), Pose2(1.5, -1.0, 0.8), Pose2(-3.0, 0.0, 0.0)}) {
    SCOPED_TRACE(offset.x);
    const bool reachable = offset.translation().norm() < 2.0;
    Slam localizer(options);
    *localizer.mutable_hex_maps() = *mapper.hex_maps();
    localizer.UseLoadedMap();
    EXPECT_EQ(localizer.tracking_state(), TrackingState::kDegraded);
    const Pose2 truth0 = drive.truth[start];
    ASSERT_TRUE(localizer.SetPose(
        Pose2(truth0.x + offset.x, truth0.y + offset.y, truth0.theta + offset.theta)));
    int ok_far = 0, lost = 0;
    ScanReport r;
    double error = 0.0;
    for (int j = 0; j < 100; ++j) {
      const Pose2& truth = drive.truth[start + j];
      r = localizer.ProcessScan(sim::SimulateScan(drive.world, truth, drive.lidar, 0.1 * j, &rng));
      error = Distance(r.pose, truth);
      if (r.tracking_state == TrackingState::kOk && error > 0.5) ++ok_far;
      if (r.tracking_state == TrackingState::kLost) {
        ++lost;
        EXPECT_EQ(r.covariance, UnknownPoseCovariance());
      }
    }
    EXPECT_EQ(ok_far, 0);
    EXPECT_GT(lost, 0);
    if (reachable) {
      EXPECT_EQ(r.tracking_state, TrackingState::kOk);
      EXPECT_LT(error, 0.03);
      EXPECT_GE(localizer.relocalizations(), 1);
    } else {
      EXPECT_EQ(r.tracking_state, TrackingState::kLost);
      EXPECT_FALSE(r.pose_from_scan);
    }
    std::cout << "started " << offset.x << ", " << offset.y << " m, " << offset.theta
              << " rad off: lost for " << lost << " scans, then " << error << " m\n";
  }
}

// No odometry, `step` m a scan down CorridorWithDoorFrames at 10 Hz; after the 15th scan the
// lidar drops `gap` scans, or (GapKind::kCluttered) sees clutter close around the robot in three
// of every four beams for `gap` scans, as with people walking by.
enum class GapKind { kDropped, kCluttered };

struct CorridorRun {
  double worst = 0.0;  // m, over every scan after the first two
  int recovered = 0;   // scans whose recovery search replaced Gauss–Newton's match
  int failed = 0;      // scans whose match was judged failed
  int lost = 0;        // scans while lost
};

CorridorRun DriveDownTheCorridor(double step, int gap, GapKind kind = GapKind::kDropped) {
  const sim::SegmentWorld corridor = CorridorWithDoorFrames();
  const sim::LidarModel lidar = FourMetreLidar();
  constexpr int kFirstInGap = 15;
  constexpr double kScanPeriod = 0.1;
  Slam slam(RoomOptions());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> clutter(0.4f, 0.8f);
  CorridorRun run;
  for (int i = 0; i < 40; ++i) {
    const bool in_gap = i >= kFirstInGap && i < kFirstInGap + gap;
    if (in_gap && kind == GapKind::kDropped) continue;
    const Pose2 truth(-3.0 + step * i, 0.1, 0.0);
    if (i == 0) slam.Reset(truth);
    LaserScan scan = sim::SimulateScan(corridor, truth, lidar, kScanPeriod * i, &rng);
    if (in_gap) {
      for (std::size_t b = 0; b < scan.ranges.size(); ++b) {
        if (b % 4 != 0) scan.ranges[b] = clutter(rng);
      }
    }
    const ScanReport r = slam.ProcessScan(scan);
    run.recovered += r.recovered ? 1 : 0;
    run.failed += r.evidence == ScanEvidence::kFailed ? 1 : 0;
    run.lost += r.tracking_state == TrackingState::kLost ? 1 : 0;
    if (i >= 2) run.worst = std::max(run.worst, Distance(r.pose, truth));
  }
  return run;
}

// 0.025-0.03 m a scan and 11-12 scans dropped, a gap longer than the prediction over a gap
// covers (kMaxPredictedPeriods): the scan after it is 0.3-0.36 m on, and the search around the
// prediction finds it. Taken as the next scan's motion, that jump put the next scan as far
// ahead again, where the door frames matched too, and the estimate ran off down the corridor
// (1.62-3.34 m at worst). Without odometry the scan after a recovery is now also matched from
// the motion before it (the jump may mend where the prediction left the pose; at 2 Hz on the
// Intel log, `IntelSubsampledTest`, the run is lost without this). Measured: 0.006 m at worst.
TEST(SlamTrackingTest, ARecoverysJumpIsNotCarriedOnAsVelocity) {
  for (const auto& [step, dropped] : {std::pair{0.025, 12}, std::pair{0.03, 11}}) {
    SCOPED_TRACE(std::to_string(step) + " m a scan, " + std::to_string(dropped) + " dropped");
    const CorridorRun run = DriveDownTheCorridor(step, dropped);
    EXPECT_GT(run.recovered, 0) << "the gap must need the recovery";
    EXPECT_LT(run.worst, 0.02);
  }
}

// 0.1-0.2 m a scan and two to four scans dropped: the previous scan's motion alone leaves the
// prediction 0.3-0.6 m short, no recovery fires, and the match settled on a door frame behind
// the robot (0.33-0.64 m off) or ran on from there. Now the scan after a gap is also matched
// from that motion once per scan period elapsed (the stamps against their running average
// interval), and the following scans from the motion per period. Measured: 0.007-0.020 m.
// (Five or more dropped at 0.15 m a scan, 0.9 m and more on a 4 m lidar, still run off.)
TEST(SlamTrackingTest, DroppedScansArePredictedOverTheGap) {
  for (const auto& [step, dropped] : {std::pair{0.10, 3}, std::pair{0.15, 2}, std::pair{0.15, 4},
                                      std::pair{0.20, 3}, std::pair{0.05, 5}}) {
    SCOPED_TRACE(std::to_string(step) + " m a scan, " + std::to_string(dropped) + " dropped");
    const CorridorRun run = DriveDownTheCorridor(step, dropped);
    EXPECT_LT(run.worst, 0.03);
    // Placed by a prediction, not found by a search: no recovery to report or to count.
    EXPECT_EQ(run.recovered, 0);
  }
}

// 0.15 m a scan and, for three or four scans, clutter close around the robot in three of every
// four beams: the matches fail (below tracking_lost_score) and the pose is the prediction's. The
// constant-velocity prediction used to stop constant_velocity_horizon (0.2 s) after the last
// match, so the pose held while the robot drove on, and the first clear scan started 0.3-0.45 m
// behind it, where the door frames matched too: 6.7 and 8.4 m off by the end (ACES without
// odometry: the pose held over five failed matches, and the robot was lost for 1900 scans). A
// failed match is no sign of a stop: the prediction now carries on over failed matches until the
// state is lost (blind scans still hold after the horizon: BlindScansDoNotPushTheEstimateAway...).
// Measured: 0.011 and 0.014 m at worst. (At 0.1 m a scan the same clutter leaves matches that
// are poor, not failed, and used: 0.22 m off either way; left to do.)
TEST(SlamTrackingTest, FailedMatchesCarryThePredictionOn) {
  for (const int cluttered : {3, 4}) {
    const double step = 0.15;
    SCOPED_TRACE(std::to_string(step) + " m a scan, " + std::to_string(cluttered) + " cluttered");
    const CorridorRun run = DriveDownTheCorridor(step, cluttered, GapKind::kCluttered);
    EXPECT_GE(run.failed, cluttered - 1) << "the clutter must fail the matches";
    EXPECT_EQ(run.lost, 0);
    EXPECT_LT(run.worst, 0.03);
    std::cout << step << " m a scan, " << cluttered << " cluttered: " << run.failed
              << " failed, worst " << run.worst << " m\n";
  }
}

// While lost the map must not change: a robot placed 2 m and 0.8 rad off in a mapping run.
TEST(SlamTrackingTest, TheMapIsNotUpdatedWhileLost) {
  RoomRun run(RoomOptions());
  for (int i = 0; i < 60; ++i) run.Scan(run.drive().truth[i]);
  const Pose2 truth = run.drive().truth[60];
  ASSERT_TRUE(run.slam().SetPose(truth * Pose2(2.0, 0.0, 0.8)));
  const int updates = run.slam().map_updates();
  const std::vector<float> cells = run.slam().hex_maps()->level(0).log_odds_grid().values();
  bool lost = false;
  for (int i = 0; i < 8; ++i) {
    const ScanReport r = run.Scan(truth);
    lost |= r.tracking_state == TrackingState::kLost;
    EXPECT_FALSE(r.map_updated);
  }
  EXPECT_TRUE(lost);
  EXPECT_EQ(run.slam().map_updates(), updates);
  EXPECT_EQ(run.slam().hex_maps()->level(0).log_odds_grid().values(), cells);
}

// A long featureless corridor: the walls say where the robot is across it, nothing says where
// along it. The along-axis sigma must dwarf the across one (the matcher's raw Hessian gave 1.7
// and 1.5 mm on the hex lattice, while the estimate slid 4 m).
TEST(SlamTrackingTest, TheCovarianceGrowsAlongACorridor) {
  for (const std::string lattice : {"hex", "square"}) {
    SCOPED_TRACE(lattice);
    sim::SegmentWorld corridor;
    corridor.AddSegment({-60.0, -1.03}, {60.0, -1.03});
    corridor.AddSegment({-60.0, 0.97}, {60.0, 0.97});
    SlamOptions options = RoomOptions();
    options.lattice = lattice;
    Slam slam(options);
    std::mt19937_64 rng(7);
    std::vector<double> along, across;
    for (int i = 0; i < 100; ++i) {
      const ScanReport r = slam.ProcessScan(
          sim::SimulateScan(corridor, Pose2(0.02 * i, 0.0, 0.0), sim::LidarModel(), 0.1 * i, &rng));
      if (!r.pose_from_scan || r.outcome != ScanOutcome::kMatched) continue;
      along.push_back(std::sqrt(r.covariance(0, 0)));
      across.push_back(std::sqrt(r.covariance(1, 1)));
    }
    ASSERT_GT(along.size(), 50u);
    std::sort(along.begin(), along.end());
    std::sort(across.begin(), across.end());
    const double median_along = along[along.size() / 2], median_across = across[across.size() / 2];
    EXPECT_GT(median_along, 1.0);             // metres: nothing constrains it
    EXPECT_LT(median_across, 0.02);           // under half a cell
    EXPECT_GT(median_along, 100.0 * median_across);
    std::cout << lattice << " corridor: median sigma along " << median_along << " m, across "
              << median_across << " m\n";
  }
}

// A slow laser on a fast robot: 3.6 m between scans along a corridor and 2 m of range, so every
// scan falls on unmapped space only (MIT CSAIL at 1 Hz: 1.8 m and 1 rad round a corner). The
// match has nothing to pull on; odometry's pose stands and the scan is mapped there, so the map
// keeps up with the robot (before, none went in, the matches wandered off odometry's pose on
// nothing, and the robot was lost once back on the map).
TEST(SlamTrackingTest, OdometryMapsScansThatFallOnUnmappedSpaceOnly) {
  const sim::SegmentWorld corridor = CorridorWithDoorFrames();
  sim::LidarModel lidar;
  lidar.range_max = 2.0;
  constexpr int kSteps = 12;
  constexpr double kStep = 3.6;
  for (const bool loop_closure : {false, true}) {
    SCOPED_TRACE(loop_closure ? "loop closure" : "single map");
    SlamOptions options = RoomOptions();
    options.loop_closure.enabled = loop_closure;
    Slam slam(options);
    std::mt19937_64 rng(11);
    ScanReport r;
    for (int i = 0; i <= kSteps; ++i) {
      const Pose2 truth(kStep * i, 0.0, 0.0);
      r = slam.ProcessScan(sim::SimulateScan(corridor, truth, lidar, 1.0 * i, &rng), Pose2(),
                           truth);
      EXPECT_LT(Distance(r.pose, truth), 1e-9) << "scan " << i;
      EXPECT_TRUE(r.map_updated) << "scan " << i;
    }
    EXPECT_EQ(slam.map_updates(), kSteps + 1);
    EXPECT_NE(r.tracking_state, TrackingState::kLost);
    // A short step on, with odometry 5 cm and 0.02 rad off: the map has kept up with the robot,
    // so the scan is matched on it, back to where the robot is.
    const Pose2 next(kStep * kSteps + 0.3, 0.0, 0.0);
    r = slam.ProcessScan(sim::SimulateScan(corridor, next, lidar, kSteps + 1.0, &rng), Pose2(),
                         next * Pose2(0.05, 0.0, 0.02));
    EXPECT_TRUE(r.pose_from_scan);
    EXPECT_LT(Distance(r.pose, next), 0.035);  // measured 0.026 (the odometry pull keeps some)
    EXPECT_LT(std::abs(r.pose.theta), 0.01);
    if (loop_closure) continue;
    // The walls half-way along are on the map where they are.
    const GridMap<HexLattice>& map = slam.hex_maps()->level(0);
    int walls = 0, cells = 0;
    for (double x = 0.5 * kStep * kSteps - 1.0; x <= 0.5 * kStep * kSteps + 1.0; x += 0.1) {
      ++cells;
      for (const double y : {-1.0, 1.0}) {
        float most = 0.0f;  // a wall on a cell border: the likelier of the cells beside it
        for (const double dy : {-0.03, 0.0, 0.03}) {
          most = std::max(most, map.Probability(map.lattice().CellOf({x, y + dy})));
        }
        walls += most > 0.5f ? 1 : 0;
      }
    }
    EXPECT_GE(walls, 0.9 * 2 * cells);  // measured: 36 of 38 (hex)
  }
}

// Lost with loop closure while driving on into space the active submap does not hold, the front
// end stayed lost for good: nothing is mapped while lost, so nothing it sees is ever on the map
// (the ACES log with odometry: lost at 575 s for the remaining 790 s). Now, lost for
// loop_closure_restart_after_lost_scans, it starts a new submap at odometry's pose and maps again;
// the submaps from before are finished as they were. A corridor with door frames, 4 m of range,
// 0.3 m a scan with exact odometry; 25 scans of random ranges (a fault, or people all round the
// laser) lose the robot; it drives on past where the map ends. The oracle is the simulator's truth.
TEST(SlamTrackingTest, LostWithLoopClosureStartsOverOnANewSubmapAndMapsAgain) {
  const sim::SegmentWorld corridor = CorridorWithDoorFrames();
  const sim::LidarModel lidar = FourMetreLidar();
  constexpr double kStep = 0.3;
  constexpr int kClean = 40, kFaulty = 25, kScans = 150;
  for (const int restart_after : {0, 20}) {
    SCOPED_TRACE(restart_after == 0 ? "never starts over" : "starts over");
    SlamOptions options = RoomOptions();
    options.loop_closure.restart_after_lost_scans = restart_after;
    Slam slam(options);
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<float> garbage(0.3f, 4.0f);
    bool lost = false;
    int updates_after_fault = 0;
    ScanReport r;
    for (int i = 0; i < kScans; ++i) {
      const Pose2 truth(kStep * i, 0.0, 0.0);
      LaserScan scan = sim::SimulateScan(corridor, truth, lidar, 0.1 * i, &rng);
      const bool faulty = i >= kClean && i < kClean + kFaulty;
      if (faulty) {
        for (float& range : scan.ranges) range = garbage(rng);
      }
      r = slam.ProcessScan(scan, Pose2(), truth);
      lost |= r.tracking_state == TrackingState::kLost;
      if (i >= kClean + kFaulty && r.map_updated) ++updates_after_fault;
    }
    const Pose2 end(kStep * (kScans - 1), 0.0, 0.0);
    EXPECT_TRUE(lost);
    if (restart_after == 0) {
      EXPECT_EQ(r.tracking_state, TrackingState::kLost);
      EXPECT_EQ(updates_after_fault, 0);
      EXPECT_EQ(slam.restarts(), 0);
    } else {
      EXPECT_EQ(r.tracking_state, TrackingState::kOk);
      EXPECT_GE(slam.restarts(), 1);
      // 0.3 m a scan, map_update_distance_thresh 0.4: every second scan once it maps again.
      EXPECT_GT(updates_after_fault, (kScans - kClean - kFaulty - 2 * restart_after) / 3);
      // The new submap starts from the lost estimate's heading (the first scans on it turned it
      // by 0.01 rad), and nothing it sees overlaps the old submaps to correct that: measured
      // 0.265 m after 25 m (a clean drive: 0.081 m; lost for good, odometry alone: 0.041 m).
      EXPECT_LT(Distance(r.pose, end), 0.4);
    }
    std::cout << (restart_after == 0 ? "never" : "starts over") << ": " << slam.restarts()
              << " restarts, " << updates_after_fault << " map updates after the fault, end "
              << Distance(r.pose, end) << " m off, " << TrackingStateName(r.tracking_state)
              << "\n";
  }
}

// Lost scans count towards loop_closure_restart_after_lost_scans only while odometry moves the
// robot: standing or turning on the spot it stays where its submap is and can find itself on
// it again (ACES stood lost at its roundabout for 50 scans and relocalized as it turned: 0.038 m;
// started over there, the near-empty new submap let that turn slip 0.2 rad: 0.175 m). Here the
// robot turns a full circle on the spot among clutter short of the corridor's walls, for three
// times the restart's count of lost scans, then drives on with clean scans: it must find its
// submap again without starting over and end where the simulator put it.
TEST(SlamTrackingTest, LostTurningOnTheSpotDoesNotStartOver) {
  const sim::SegmentWorld corridor = CorridorWithDoorFrames();
  const sim::LidarModel lidar = FourMetreLidar();
  constexpr double kStep = 0.3;
  constexpr int kClean = 40, kTurning = 60, kScans = 150;
  constexpr float kNearest = 0.3f;  // m
  SlamOptions options = RoomOptions();
  options.loop_closure.restart_after_lost_scans = 20;
  Slam slam(options);
  std::mt19937_64 rng(13);
  bool lost = false;
  int updates_after_fault = 0;
  ScanReport r;
  for (int i = 0; i < kScans; ++i) {
    const bool turning = i >= kClean && i < kClean + kTurning;
    const int moving_steps = i < kClean ? i : std::max(kClean, i - kTurning);
    const double heading = turning ? 2.0 * M_PI * (i - kClean) / kTurning : 0.0;
    const Pose2 truth(kStep * moving_steps, 0.0, NormalizeAngle(heading));
    LaserScan scan = sim::SimulateScan(corridor, truth, lidar, 0.1 * i, &rng);
    if (turning) {
      // People and clutter between the laser and the walls, on the corridor's mapped floor.
      for (float& range : scan.ranges) {
        if (range > kNearest) range = std::uniform_real_distribution<float>(kNearest, range)(rng);
      }
    }
    r = slam.ProcessScan(scan, Pose2(), truth);
    lost |= r.tracking_state == TrackingState::kLost;
    if (i >= kClean + kTurning && r.map_updated) ++updates_after_fault;
  }
  const Pose2 end(kStep * (kScans - 1 - kTurning), 0.0, 0.0);
  std::cout << slam.restarts() << " restarts, " << updates_after_fault
            << " map updates after the fault, end " << Distance(r.pose, end) << " m off, "
            << TrackingStateName(r.tracking_state) << "\n";
  EXPECT_TRUE(lost);
  EXPECT_EQ(slam.restarts(), 0);
  EXPECT_EQ(r.tracking_state, TrackingState::kOk);
  EXPECT_GT(updates_after_fault, (kScans - kClean - kTurning) / 3);
  EXPECT_LT(Distance(r.pose, end), 0.08);
}

// Lost with odometry in a corridor after garbage scans, the robot drives on past what was
// mapped: the match at odometry's prediction cannot be scored, and the lost search (+-pi) used
// to take the place turned by pi that put the scan back on the mapped half (score 0.96). The
// matches then walked backwards against odometry, state ok, 42.9 m off 72 scans later. Oracle:
// the simulator's truth, which odometry gives exactly here.
TEST(SlamTrackingTest, LostWithOdometryNeverTakesAPlaceTheMapCannotJudgeAgainstIt) {
  const sim::SegmentWorld corridor = CorridorWithDoorFrames();
  const sim::LidarModel lidar = FourMetreLidar();
  constexpr double kStep = 0.3;
  constexpr int kClean = 40, kFaulty = 8, kScans = 120;
  SlamOptions options = RoomOptions();
  Slam slam(options);
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<float> garbage(0.3f, 4.0f);
  bool lost = false;
  double worst_trusted = 0.0, worst_heading = 0.0;
  ScanReport r;
  for (int i = 0; i < kScans; ++i) {
    const Pose2 truth(kStep * i, 0.0, 0.0);
    LaserScan scan = sim::SimulateScan(corridor, truth, lidar, 0.1 * i, &rng);
    if (i >= kClean && i < kClean + kFaulty) {
      for (float& range : scan.ranges) range = garbage(rng);
    }
    r = slam.ProcessScan(scan, Pose2(), truth);
    lost |= r.tracking_state == TrackingState::kLost;
    if (r.tracking_state == TrackingState::kLost) continue;
    worst_trusted = std::max(worst_trusted, Distance(r.pose, truth));
    worst_heading = std::max(worst_heading, std::abs(NormalizeAngle(r.pose.theta - truth.theta)));
  }
  const Pose2 end(kStep * (kScans - 1), 0.0, 0.0);
  std::cout << slam.restarts() << " restarts; not lost, at worst " << worst_trusted << " m and "
            << worst_heading << " rad off; end " << Distance(r.pose, end) << " m off, "
            << TrackingStateName(r.tracking_state) << "\n";
  EXPECT_TRUE(lost);
  EXPECT_LT(worst_heading, 0.02);  // measured 0.005 rad (before: pi)
  EXPECT_LT(worst_trusted, 0.15);  // measured 0.066 m (before: 43.5 m)
  EXPECT_EQ(r.tracking_state, TrackingState::kOk);
}

// Below tracking_ok_score a match did not go into the map, and where the score sinks for a
// while though the pose is right (a hall seen from afar or through clutter: the ACES log at
// 505 s, the Freiburg hospital at scan 75) the map was no longer drawn and the robot was lost
// where it ended. With loop closure, a poor match now goes in when it lies within
// loop_closure_odometry_confirms_distance/_angle of odometry's prediction, and only then.
// tracking_ok_score 0.99 makes right matches poor here; the corridor holds the robot sideways,
// so odometry drifting sideways 8 cm a scan does not confirm them. The oracle is the prediction
// computed from the odometry the test gives, and the simulator's truth.
TEST(SlamTrackingTest, PoorMatchesGoInOnlyWhereOdometryConfirmsThem) {
  const sim::SegmentWorld corridor = CorridorWithDoorFrames();
  const sim::LidarModel lidar = FourMetreLidar();
  constexpr double kStep = 0.3;
  constexpr int kScans = 120;
  struct Case { double confirms; double sideways; const char* name; };
  for (const Case c : {Case{0.0, 0.0, "never"}, Case{0.05, 0.0, "confirms"},
                       Case{0.05, 0.08, "odometry sideways"}}) {
    SCOPED_TRACE(c.name);
    SlamOptions options = RoomOptions();
    options.tracking.ok_score = 0.99;
    options.loop_closure.odometry_confirms_distance = c.confirms;
    options.loop_closure.restart_after_lost_scans = 0;
    Slam slam(options);
    std::mt19937_64 rng(17);
    int poor = 0, poor_inserted = 0;
    double farthest_inserted = 0.0;
    ScanReport r;
    Pose2 odometry_before;
    for (int i = 0; i < kScans; ++i) {
      const Pose2 truth(kStep * i, 0.0, 0.0);
      const Pose2 odometry(kStep * i, c.sideways * i, 0.0);
      const Pose2 predicted = r.pose * RelativePose(odometry_before, odometry);
      odometry_before = odometry;
      r = slam.ProcessScan(sim::SimulateScan(corridor, truth, lidar, 0.1 * i, &rng), Pose2(),
                           odometry);
      if (i == 0 || r.evidence != ScanEvidence::kPoor || !r.pose_from_scan) continue;
      ++poor;
      if (!r.map_updated) continue;
      ++poor_inserted;
      farthest_inserted = std::max(farthest_inserted, Distance(r.pose, predicted));
    }
    const Pose2 end(kStep * (kScans - 1), 0.0, 0.0);
    std::cout << c.name << ": " << poor << " poor, " << poor_inserted << " inserted, farthest "
              << farthest_inserted << ", end " << Distance(r.pose, end) << " m off, "
              << TrackingStateName(r.tracking_state) << "\n";
    EXPECT_GT(poor, 20);  // measured 27 and 46
    EXPECT_LE(farthest_inserted, 0.05 + 1e-9);
    if (c.confirms == 0.0) {
      EXPECT_EQ(poor_inserted, 0);
    } else if (c.sideways == 0.0) {
      EXPECT_EQ(poor_inserted, poor);  // each within 4 mm of the prediction
      EXPECT_LT(Distance(r.pose, end), 0.05);  // measured 0.038 (never: 0.035)
    } else {
      EXPECT_LT(poor_inserted, poor / 10);  // measured 1 of 46
    }
  }
}

// A map whose cells are NaN (a corrupt file read past its checks) must not put NaN into a pose,
// a covariance or the map; the state says lost, and a clean map brings it back. The single map
// (loop closure off): the one the front end matches against is the one poisoned here.
TEST(SlamTrackingTest, APoisonedMapNeverYieldsANonFinitePoseAndTrackingRecovers) {
  SlamOptions options = RoomOptions();
  options.loop_closure.enabled = false;
  RoomRun run(options);
  for (int i = 0; i < 30; ++i) run.Scan(run.drive().truth[i]);
  const MapPyramid<HexLattice> clean = *run.slam().hex_maps();
  MapPyramid<HexLattice>* maps = run.slam().mutable_hex_maps();
  for (int level = 0; level < maps->size(); ++level) {
    GridMap<HexLattice>& grid = maps->mutable_level(level);
    grid.Assign(grid.rect(), std::vector<float>(grid.rect().size(),
                                                std::numeric_limits<float>::quiet_NaN()));
  }
  bool lost = false;
  for (int i = 30; i < 40; ++i) {
    const ScanReport r = run.Scan(run.drive().truth[i]);
    EXPECT_TRUE(IsFinite(r.pose));
    EXPECT_TRUE(r.covariance.allFinite());
    EXPECT_FALSE(r.map_updated);
    lost |= r.tracking_state == TrackingState::kLost;
  }
  EXPECT_TRUE(lost);
  *maps = clean;
  ScanReport r;
  for (int i = 40; i < 60; ++i) r = run.Scan(run.drive().truth[i]);
  EXPECT_EQ(r.tracking_state, TrackingState::kOk);
  EXPECT_LT(Distance(r.pose, run.drive().truth[59]), 0.05);
}

// With odometry, the search while lost looks at headings within
// tracking_lost_search_odometry_angular_window of odometry's (plus a share of its turning since):
// MIT Killian, lost for three scans in a corridor, took a place turned by pi and mapped on
// backwards. Here the robot stands at (-0.75, 0) in a room that looks the same turned by pi about
// its centre; while garbage scans lose it, its odometry jumps `slip` metres ahead (a wheel spun
// on the spot), and stays there. Oracle: the simulator's truth, and the room's symmetry, which puts
// a perfect fit turned by pi at (0.75, 0).
struct SlipRun {
  double worst_ok = 0.0;       // m from the truth, over scans reported ok
  double worst_heading = 0.0;  // rad from the truth's heading (0), over every scan
  TrackingState end_state = TrackingState::kOk;
};

SlipRun StandStillWhileOdometrySlips(double slip, double odometry_angular_window) {
  const sim::SegmentWorld room = PointSymmetricRoom();
  constexpr int kFirstFaulty = 25, kFaulty = 7, kScans = 45;
  SlamOptions options = RoomOptions();
  options.tracking.lost_search_odometry_angular_window = odometry_angular_window;
  Slam slam(options);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> garbage(0.3f, 4.0f);
  SlipRun run;
  ScanReport r;
  for (int i = 0; i < kScans; ++i) {
    const Pose2 truth(std::min(-3.0 + 0.15 * i, -0.75), 0.0, 0.0);
    if (i == 0) slam.Reset(truth);
    LaserScan scan = sim::SimulateScan(room, truth, sim::LidarModel(), 0.1 * i, &rng);
    if (i >= kFirstFaulty && i < kFirstFaulty + kFaulty) {
      for (float& range : scan.ranges) range = garbage(rng);
    }
    const Pose2 odometry(truth.x + (i >= kFirstFaulty ? slip : 0.0), 0.0, 0.0);
    r = slam.ProcessScan(scan, Pose2(), odometry);
    run.worst_heading = std::max(run.worst_heading, std::abs(NormalizeAngle(r.pose.theta)));
    if (r.tracking_state == TrackingState::kOk) {
      run.worst_ok = std::max(run.worst_ok, Distance(r.pose, truth));
    }
  }
  run.end_state = r.tracking_state;
  std::cout << "slip " << slip << " m, heading window " << odometry_angular_window << " rad: "
            << run.worst_ok << " m off at worst while ok, heading " << run.worst_heading
            << " rad, " << TrackingStateName(run.end_state) << " at the end\n";
  return run;
}

TEST(SlamTrackingTest, LostWithOdometryTakesNoPlaceAtAHeadingOdometryRulesOut) {
  const double window = TrackingOptions().lost_search_odometry_angular_window;
  // 1.5 m: the right place lies beyond the search's 1 m, the place turned by pi inside it. The
  // robot stays lost, where every heading searched took that place and called it ok.
  const SlipRun far = StandStillWhileOdometrySlips(1.5, window);
  EXPECT_LT(far.worst_heading, 0.01);  // measured 0.0016 rad
  EXPECT_LT(far.worst_ok, 0.02);       // measured 0.005 m, before the garbage
  EXPECT_EQ(far.end_state, TrackingState::kLost);
  const SlipRun every_heading = StandStillWhileOdometrySlips(1.5, M_PI);
  EXPECT_GT(every_heading.worst_heading, 3.0);  // the trap: measured 3.1414 rad,
  EXPECT_GT(every_heading.worst_ok, 1.0);       // 1.50 m off, and ok
  EXPECT_EQ(every_heading.end_state, TrackingState::kOk);
  // 0.9 m: both lie inside it; the right one is found, as it was.
  const SlipRun near = StandStillWhileOdometrySlips(0.9, window);
  EXPECT_LT(near.worst_heading, 0.01);
  EXPECT_LT(near.worst_ok, 0.02);  // measured 0.005 m
  EXPECT_EQ(near.end_state, TrackingState::kOk);
}


}  // namespace
}  // namespace hex_slam
