#include "hex_slam/mapping/tracking_state.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "hex_slam/geometry/hex_lattice.h"
#include "hex_slam/matching/match_covariance.h"
#include "../test_maps.h"

namespace hex_slam {
namespace {

const double kNaN = std::nan("");

TEST(TrackingMonitorTest, OnePoorMatchDegradesAndGoodOnesInARowRestoreOk) {
  TrackingOptions o;
  TrackingMonitor m(o);
  EXPECT_EQ(m.state(), TrackingState::kOk);
  EXPECT_TRUE(m.Update(ScanEvidence::kPoor, 0.75));
  EXPECT_EQ(m.state(), TrackingState::kDegraded);
  EXPECT_NE(m.reason().find("0.75"), std::string::npos) << m.reason();
  for (int i = 1; i < o.ok_after_scans; ++i) {
    EXPECT_FALSE(m.Update(ScanEvidence::kGood, 0.9));
    EXPECT_EQ(m.state(), TrackingState::kDegraded);
  }
  // A poor match in between starts the count again.
  EXPECT_FALSE(m.Update(ScanEvidence::kPoor, 0.75));
  for (int i = 1; i < o.ok_after_scans; ++i) m.Update(ScanEvidence::kGood, 0.9);
  EXPECT_EQ(m.state(), TrackingState::kDegraded);
  EXPECT_TRUE(m.Update(ScanEvidence::kGood, 0.9));
  EXPECT_EQ(m.state(), TrackingState::kOk);
}

TEST(TrackingMonitorTest, FailedOrBlindScansInARowLoseTrackAndOnlyGoodOnesEndIt) {
  TrackingOptions o;
  TrackingMonitor m(o);
  for (int i = 1; i < o.lost_after_scans; ++i) {
    m.Update(i % 2 ? ScanEvidence::kFailed : ScanEvidence::kBlind, 0.2);
    EXPECT_EQ(m.state(), TrackingState::kDegraded);
  }
  EXPECT_TRUE(m.Update(ScanEvidence::kBlind, kNaN));
  EXPECT_EQ(m.state(), TrackingState::kLost);
  EXPECT_NE(m.reason().find("in a row"), std::string::npos) << m.reason();
  // Poor matches, odometry alone, a pose set from outside: still lost.
  m.Update(ScanEvidence::kPoor, 0.75);
  m.Update(ScanEvidence::kOdometryOnly, kNaN);
  m.Update(ScanEvidence::kUnconfirmed, kNaN);
  EXPECT_EQ(m.state(), TrackingState::kLost);
  for (int i = 0; i < o.ok_after_scans; ++i) m.Update(ScanEvidence::kGood, 0.95);
  EXPECT_EQ(m.state(), TrackingState::kOk);
}

TEST(TrackingMonitorTest, AGoodMatchBetweenFailuresRestartsTheCount) {
  TrackingOptions o;
  o.lost_after_scans = 3;
  TrackingMonitor m(o);
  m.Update(ScanEvidence::kFailed, 0.1);
  m.Update(ScanEvidence::kFailed, 0.1);
  m.Update(ScanEvidence::kGood, 0.9);
  m.Update(ScanEvidence::kFailed, 0.1);
  m.Update(ScanEvidence::kFailed, 0.1);
  EXPECT_EQ(m.state(), TrackingState::kDegraded);
  m.Update(ScanEvidence::kFailed, 0.1);
  EXPECT_EQ(m.state(), TrackingState::kLost);
  EXPECT_FALSE(m.Lose("again"));
  m.Reset();
  EXPECT_EQ(m.state(), TrackingState::kOk);
  EXPECT_TRUE(m.Lose("poisoned"));
  EXPECT_EQ(m.reason(), "poisoned");
}

TEST(TrackingMonitorTest, EvidenceFollowsTheThresholds) {
  TrackingOptions o;
  MatchScore s;
  s.score = o.ok_score;
  EXPECT_EQ(MatchEvidence(o, s, true, true), ScanEvidence::kGood);
  s.score = o.lost_score;
  EXPECT_EQ(MatchEvidence(o, s, true, true), ScanEvidence::kPoor);
  s.score = o.lost_score - 0.01;
  EXPECT_EQ(MatchEvidence(o, s, true, true), ScanEvidence::kFailed);
  s.score = 1.0;
  EXPECT_EQ(MatchEvidence(o, s, false, true), ScanEvidence::kFailed);
  s.score = kNaN;  // unscored: exploring while mapping, off the map while localizing
  EXPECT_EQ(MatchEvidence(o, s, true, true), ScanEvidence::kPoor);
  EXPECT_EQ(MatchEvidence(o, s, true, false), ScanEvidence::kFailed);
  s.known_agreement = o.lost_score - 0.01;  // what is on the map contradicts it
  EXPECT_EQ(MatchEvidence(o, s, true, true), ScanEvidence::kFailed);
}

TEST(TrackingOptionsTest, InvalidValuesAreNamed) {
  TrackingOptions o;
  EXPECT_TRUE(o.Validate().empty());
  o.lost_score = 0.9;  // above ok_score
  o.ok_after_scans = 0;
  o.lost_search_angular_window = 4.0;
  const std::vector<std::string> errors = o.Validate();
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_NE(errors[0].find("tracking_lost_score"), std::string::npos);
}

// The score's oracle is the simulator: the scan taken at the true pose agrees with the map made
// from the same room, the same scan placed 1.5 m off does not.
TEST(ScoreMatchTest, TheTruePoseAgreesAndAPoseOffDoesNot) {
  const MapPyramid<HexLattice> maps = testing_util::MapOfTestRoom<HexLattice>(0.05);
  const sim::SegmentWorld world = testing_util::GenericRoom();
  std::mt19937_64 rng(3);
  const Pose2 truth = testing_util::GenericPlacement() * Pose2(-1.0, 0.5, 0.4);
  const std::vector<Eigen::Vector2d> points =
      testing_util::ScanPoints(world, truth, sim::LidarModel(), &rng);
  const MatchScore right = ScoreMatch(maps.level(1), points, truth, 0.5, 20);
  ASSERT_TRUE(right.scored());
  EXPECT_GT(right.score, 0.9);
  EXPECT_EQ(right.points, static_cast<int>(points.size()));
  const MatchScore off = ScoreMatch(maps.level(1), points, truth * Pose2(1.5, 0.0, 0.0), 0.5, 20);
  ASSERT_TRUE(off.scored());
  EXPECT_LT(off.score, TrackingOptions().lost_score);
  // Far outside the map nothing is known: unscored.
  EXPECT_FALSE(ScoreMatch(maps.level(1), points, Pose2(500.0, 0.0, 0.0), 0.5, 20).scored());
}

TEST(SurfaceNormalsTest, AStraightWallHasItsNormalAndACornerSplitsIt) {
  // An L: 30 points along x (y = 2), then 30 up the wall x = 3; 1 cm of noise.
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 30; ++i) points.emplace_back(0.1 * i, 2.0 + noise(rng));
  for (int i = 1; i <= 30; ++i) points.emplace_back(3.0 + noise(rng), 2.0 + 0.1 * i);
  points.emplace_back(10.0, 10.0);  // an isolated return
  const std::vector<Eigen::Vector2d> normals = SurfaceNormals(points);
  for (int i = 2; i < 27; ++i) EXPECT_NEAR(std::abs(normals[i].y()), 1.0, 1e-3) << i;
  for (int i = 33; i < 58; ++i) EXPECT_NEAR(std::abs(normals[i].x()), 1.0, 1e-3) << i;
  EXPECT_TRUE(normals.back().isZero());
}

TEST(MatchCovarianceTest, UnknownWithoutAMatchAndNeverNotFinite) {
  MatchResult none;
  EXPECT_EQ(MatchCovariance(none, {}), UnknownPoseCovariance());
  MatchResult poisoned;
  poisoned.num_points = 100;
  poisoned.hessian = Eigen::Matrix3d::Identity();
  poisoned.cost = std::nan("");
  EXPECT_EQ(MatchCovariance(poisoned, {}), UnknownPoseCovariance());
}

}  // namespace
}  // namespace hex_slam
