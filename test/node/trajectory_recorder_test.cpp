#include "trajectory_recorder.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

TEST(TrajectoryRecorderTest, KeepsAPosePerStepOfDistanceOrAngle) {
  TrajectoryRecorder recorder(0.1, 0.2, 1000);
  EXPECT_TRUE(recorder.Add(0.0, Pose2(0.0, 0.0, 0.0)));
  EXPECT_FALSE(recorder.Add(0.1, Pose2(0.05, 0.0, 0.0)));
  EXPECT_TRUE(recorder.Add(0.2, Pose2(0.1, 0.0, 0.0)));
  EXPECT_FALSE(recorder.Add(0.3, Pose2(0.1, 0.0, 0.1)));
  EXPECT_TRUE(recorder.Add(0.4, Pose2(0.1, 0.0, 0.25)));  // turning in place counts
  ASSERT_EQ(recorder.poses().size(), 3u);
  EXPECT_EQ(recorder.poses()[2].stamp, 0.4);
  recorder.Clear();
  EXPECT_TRUE(recorder.poses().empty());
}

TEST(TrajectoryRecorderTest, ThinsToHalfAtTheCapAndKeepsTheWholeRun) {
  TrajectoryRecorder recorder(0.0, 0.0, 8);
  for (int i = 0; i < 100; ++i) recorder.Add(i, Pose2(0.1 * i, 0.0, 0.0));
  EXPECT_LE(recorder.poses().size(), 8u);
  EXPECT_GE(recorder.poses().size(), 4u);
  EXPECT_EQ(recorder.poses().front().stamp, 0.0);   // the start survives thinning
  EXPECT_EQ(recorder.poses().back().stamp, 99.0);   // and the latest pose is there
  for (std::size_t i = 1; i < recorder.poses().size(); ++i) {
    EXPECT_LT(recorder.poses()[i - 1].stamp, recorder.poses()[i].stamp);
  }
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
