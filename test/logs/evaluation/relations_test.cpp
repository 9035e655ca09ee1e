#include "hex_slam/logs/evaluation/relations.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "hex_slam/logs/carmen_reader.h"
#include "test_data.h"

namespace hex_slam {
namespace logs {
namespace {

constexpr double kDeg = 180.0 / M_PI;

TEST(RelationsTest, MotionIsComparedInTheFirstPosesFrame) {
  // The robot faces +y and moves 1 m along it: 1 m straight ahead in its own frame.
  const std::vector<io::StampedPose> trajectory = {{0.0, Pose2(5, 5, M_PI / 2)},
                                                   {1.0, Pose2(5, 6, M_PI / 2)}};
  const RelationsReport exact =
      EvaluateRelations(trajectory, {{0.0, 1.0, Pose2(1, 0, 0)}}, RelationsOptions());
  EXPECT_EQ(exact.evaluated, 1);
  EXPECT_NEAR(exact.translation.mean, 0.0, 1e-12);
  EXPECT_NEAR(exact.rotation.mean, 0.0, 1e-12);
  // Compared in the world frame, this one would be the exact one.
  const RelationsReport world =
      EvaluateRelations(trajectory, {{0.0, 1.0, Pose2(0, 1, 0)}}, RelationsOptions());
  EXPECT_NEAR(world.translation.mean, std::sqrt(2.0), 1e-12);
}

TEST(RelationsTest, HandComputedErrorsAndTheirSquares) {
  const std::vector<io::StampedPose> trajectory = {
      {0.0, Pose2(0, 0, 0)}, {1.0, Pose2(1, 0, 0.2)}, {2.0, Pose2(1, 1, 0.2)}};
  // Relation 1: 0.1 m and 0.1 rad off. Relation 2 (t1 = 1, t2 = 2): the motion is
  // R(-0.2) (0, 1) = (sin 0.2, cos 0.2); reference 0.3 m further ahead, heading exact.
  const Pose2 m2(std::sin(0.2), std::cos(0.2) + 0.3, 0.0);
  const std::vector<Relation> relations = {{0.0, 1.0, Pose2(1.1, 0, 0.3)}, {1.0, 2.0, m2}};
  const RelationsReport r = EvaluateRelations(trajectory, relations, RelationsOptions());
  ASSERT_EQ(r.evaluated, 2);
  EXPECT_NEAR(r.translation.mean, 0.2, 1e-12);
  EXPECT_NEAR(r.translation.stddev, 0.1, 1e-12);
  EXPECT_NEAR(r.translation_squared.mean, 0.05, 1e-12);    // (0.01 + 0.09) / 2
  EXPECT_NEAR(r.translation_squared.stddev, 0.04, 1e-12);
  EXPECT_NEAR(r.rotation.mean, 0.05 * kDeg, 1e-9);  // 0.1 rad and 0
  EXPECT_NEAR(r.rotation_squared.mean, 0.5 * (0.1 * kDeg) * (0.1 * kDeg), 1e-9);
}

TEST(RelationsTest, RotationErrorWrapsAroundPi) {
  const std::vector<io::StampedPose> trajectory = {{0.0, Pose2(0, 0, 0)}, {1.0, Pose2(0, 0, 3.1)}};
  const RelationsReport r =
      EvaluateRelations(trajectory, {{0.0, 1.0, Pose2(0, 0, -3.1)}}, RelationsOptions());
  EXPECT_NEAR(r.rotation.mean, (2 * M_PI - 6.2) * kDeg, 1e-9);
}

TEST(RelationsTest, RelationsOutsideTheTrajectoryAreSkippedAndOffsetShiftsClocks) {
  const std::vector<io::StampedPose> trajectory = {{0.0, Pose2(0, 0, 0)}, {1.0, Pose2(1, 0, 0)}};
  const std::vector<Relation> relations = {{100.0, 101.0, Pose2(1, 0, 0)},
                                           {100.0, 150.0, Pose2(1, 0, 0)}};
  EXPECT_EQ(EvaluateRelations(trajectory, relations, RelationsOptions()).evaluated, 0);
  RelationsOptions shifted;
  shifted.offset = 100.0;
  const RelationsReport r = EvaluateRelations(trajectory, relations, shifted);
  EXPECT_EQ(r.relations, 2);
  EXPECT_EQ(r.evaluated, 1);
  EXPECT_NEAR(r.translation.mean, 0.0, 1e-12);
}

TEST(RelationsTest, ReadsTheFreiburgFormatAndNamesABadLine) {
  const std::string path = ::testing::TempDir() + "/relations_test.relations";
  {
    std::ofstream out(path);
    out << "# comment\n10.5 11.5 0.1 -0.2 0 0 0 0.3\n\n12 13 1 2 0 0 0 -0.5\n";
  }
  std::vector<Relation> relations;
  ASSERT_EQ(ReadRelations(path, &relations), "");
  ASSERT_EQ(relations.size(), 2u);
  EXPECT_EQ(relations[0].t1, 10.5);
  EXPECT_EQ(relations[0].motion.y, -0.2);
  EXPECT_EQ(relations[1].motion.theta, -0.5);
  {
    std::ofstream out(path);
    out << "10.5 11.5 0.1 -0.2 0 0 0 0.3\n10 11 0.1 nan 0 0 0 0\n";
  }
  EXPECT_NE(ReadRelations(path, &relations).find(":2:"), std::string::npos);
  {
    std::ofstream out(path);
    out << "10.5 11.5 0.1\n";  // truncated
  }
  EXPECT_NE(ReadRelations(path, &relations).find(":1:"), std::string::npos);
  EXPECT_NE(ReadRelations(path + ".missing", &relations).find("cannot read"), std::string::npos);
  std::remove(path.c_str());
}

// The published floor: the Intel log's raw odometry scores 3.53 m / 41.1° on these relations.
TEST(RelationsTest, RawOdometryOnTheIntelSubsetScoresThePublishedFloor) {
  const std::string log_path = test::DataFile(test::kIntelLog);
  const std::string relations_path = test::DataFile(test::kIntelRelations);
  HEX_SLAM_REQUIRE_DATA(log_path);
  HEX_SLAM_REQUIRE_DATA(relations_path);
  CarmenLog log;
  ASSERT_EQ(ReadCarmenLog(log_path, CarmenReadOptions(), &log), "");
  std::vector<io::StampedPose> odometry;
  for (const LogScan& s : log.scans) odometry.push_back({s.scan.stamp, *s.odometry});
  std::vector<Relation> relations;
  ASSERT_EQ(ReadRelations(relations_path, &relations), "");
  const RelationsReport r = EvaluateRelations(odometry, relations, RelationsOptions());
  EXPECT_EQ(r.relations, 2984);
  EXPECT_EQ(r.evaluated, 1030);
  EXPECT_NEAR(r.translation.mean, 3.53, 0.005);
  EXPECT_NEAR(r.rotation.mean, 41.1, 0.05);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
