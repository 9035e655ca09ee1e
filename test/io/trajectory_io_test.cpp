#include "hex_slam/io/trajectory_io.h"

#include <cmath>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

TEST(TrajectoryIoTest, RoundTripKeepsPosesAndHeadings) {
  testing_util::TempDir dir;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  std::vector<StampedPose> poses;
  for (int i = 0; i < 100; ++i) poses.push_back({1e9 + 0.2 * i, Pose2(u(rng), u(rng), u(rng))});
  ASSERT_EQ(WriteTumTrajectory(dir.File("t.tum"), poses), "");
  std::vector<StampedPose> back;
  ASSERT_EQ(ReadTumTrajectory(dir.File("t.tum"), &back), "");
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back[i].stamp, poses[i].stamp, 1e-6);
    EXPECT_NEAR(back[i].pose.x, poses[i].pose.x, 1e-6);
    EXPECT_NEAR(std::abs(NormalizeAngle(back[i].pose.theta - poses[i].pose.theta)), 0.0, 1e-8);
  }
}

TEST(TrajectoryIoTest, BadLineIsNamed) {
  testing_util::TempDir dir;
  std::ofstream(dir.File("bad.tum")) << "# header\n1 2 3 0 0 0 0 1\n1 2 3 nope\n";
  std::vector<StampedPose> poses;
  EXPECT_NE(ReadTumTrajectory(dir.File("bad.tum"), &poses).find(":3:"), std::string::npos);
  EXPECT_NE(ReadTumTrajectory(dir.File("missing.tum"), &poses), "");
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
