#include "hex_slam/sim/simulated_robot.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hex_slam/sim/segment_world.h"
#include "hex_slam/sim/waypoint_path.h"

namespace hex_slam {
namespace sim {
namespace {

constexpr double kDt = 0.1;

SegmentWorld Box() {
  SegmentWorld w;
  w.AddRectangle({-5.0, -5.0}, {5.0, 5.0});
  w.AddSegment({2.0, -1.0}, {2.0, 1.0});  // a thin wall ahead of the robot
  return w;
}

TEST(SimulatedRobotTest, FollowsThePathOnePosePerStepThenStops) {
  const SegmentWorld world = Box();
  const std::vector<Pose2> path =
      SampleWaypointPath({{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}}, 0.0, PathMotion());
  SimulatedRobot robot(world, path, Pose2(), RobotOptions());
  EXPECT_TRUE(robot.following_path());
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Pose2& p = robot.Step(kDt * i, kDt);
    ASSERT_EQ(p.x, path[i].x);
    ASSERT_EQ(p.theta, path[i].theta);
  }
  EXPECT_TRUE(robot.path_finished());
  const Pose2 end = robot.pose();
  robot.Step(100.0, kDt);
  EXPECT_EQ(robot.pose().x, end.x);
  EXPECT_NEAR(robot.linear_velocity(), 0.0, 1e-12);
}

TEST(SimulatedRobotTest, VelocityCommandsDriveExactArcs) {
  const SegmentWorld world = Box();
  SimulatedRobot robot(world, {}, Pose2(-1.0, -2.0, 0.0), RobotOptions());
  EXPECT_FALSE(robot.path_finished());
  // A full circle of radius 0.5 m in 40 steps: back at the start.
  const double w = 2.0 * M_PI / (40 * kDt);
  for (int i = 1; i <= 40; ++i) {
    robot.CommandVelocity(0.5 * w, w, kDt * i);
    robot.Step(kDt * i, kDt);
    if (i == 20) {
      EXPECT_NEAR(robot.pose().y, -1.0, 1e-9);  // half way: the top of the circle
    }
  }
  EXPECT_NEAR(robot.pose().x, -1.0, 1e-9);
  EXPECT_NEAR(robot.pose().y, -2.0, 1e-9);
  EXPECT_NEAR(robot.linear_velocity(), 0.5 * w, 1e-12);
  EXPECT_NEAR(robot.angular_velocity(), w, 1e-9);
}

TEST(SimulatedRobotTest, StopsWhenCommandsStop) {
  const SegmentWorld world = Box();
  RobotOptions options;
  options.cmd_vel_timeout = 0.25;
  SimulatedRobot robot(world, {}, Pose2(-3.0, 0.0, 0.0), options);
  robot.CommandVelocity(1.0, 0.0, 0.0);
  robot.Step(0.1, kDt);
  robot.Step(0.2, kDt);
  EXPECT_NEAR(robot.pose().x, -2.8, 1e-12);
  robot.Step(0.3, kDt);  // 0.3 s after the command: stopped
  EXPECT_NEAR(robot.pose().x, -2.8, 1e-12);
  EXPECT_EQ(robot.linear_velocity(), 0.0);
}

TEST(SimulatedRobotTest, StallsInFrontOfAWallInsteadOfPassingIt) {
  const SegmentWorld world = Box();
  RobotOptions options;
  options.radius = 0.2;
  SimulatedRobot robot(world, {}, Pose2(0.0, 0.0, 0.0), options);
  // 1 m per step: without the check the robot would jump over the wall at x = 2.
  for (int i = 1; i <= 10; ++i) {
    robot.CommandVelocity(10.0, 0.0, kDt * i);
    robot.Step(kDt * i, kDt);
  }
  EXPECT_TRUE(robot.stalled());
  EXPECT_LT(robot.pose().x, 2.0 - options.radius);
  // Turning away is allowed, and then driving on.
  robot.CommandVelocity(0.0, M_PI / (2 * kDt), 1.1);
  robot.Step(1.1, kDt);
  EXPECT_FALSE(robot.stalled());
  EXPECT_NEAR(robot.pose().theta, M_PI / 2, 1e-9);
  robot.CommandVelocity(1.0, 0.0, 1.2);
  robot.Step(1.2, kDt);
  EXPECT_FALSE(robot.stalled());
  EXPECT_GT(robot.pose().y, 0.09);
}

TEST(SimulatedRobotTest, ACommandTakesOverFromThePath) {
  const SegmentWorld world = Box();
  const std::vector<Pose2> path = SampleWaypointPath({{0.0, 0.0}, {1.0, 0.0}}, 0.0, PathMotion());
  SimulatedRobot robot(world, path, Pose2(), RobotOptions());
  robot.Step(0.1, kDt);
  robot.CommandVelocity(0.0, 1.0, 0.1);
  EXPECT_FALSE(robot.following_path());
  const double x = robot.pose().x;
  robot.Step(0.2, kDt);
  EXPECT_EQ(robot.pose().x, x);
  EXPECT_NEAR(robot.pose().theta, 0.1, 1e-12);
  robot.CommandVelocity(std::nan(""), 0.0, 0.2);  // ignored
  robot.Step(0.3, kDt);
  EXPECT_NEAR(robot.pose().theta, 0.2, 1e-12);
}

}  // namespace
}  // namespace sim
}  // namespace hex_slam
