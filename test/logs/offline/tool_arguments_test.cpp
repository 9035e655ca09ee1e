#include "hex_slam/logs/offline/tool_arguments.h"

#include <gtest/gtest.h>

namespace hex_slam {
namespace logs {
namespace {

TEST(ToolArgumentsTest, NumbersMustBeWholeAndFinite) {
  double v = 0.0;
  EXPECT_TRUE(ParseNumber("-0.25", &v));
  EXPECT_EQ(v, -0.25);
  EXPECT_TRUE(ParseNumber("1e3", &v));
  EXPECT_EQ(v, 1000.0);
  for (const char* bad : {"", "0.5m", "nan", "inf", "1,2", " "}) EXPECT_FALSE(ParseNumber(bad, &v)) << bad;
}

TEST(ToolArgumentsTest, PosesAreThreeCommaSeparatedNumbers) {
  Pose2 p;
  ASSERT_TRUE(ParsePose("0.1,-0.2,3.14", &p));
  EXPECT_EQ(p.x, 0.1);
  EXPECT_EQ(p.y, -0.2);
  EXPECT_EQ(p.theta, 3.14);
  for (const char* bad : {"", "1,2", "1,2,3,4", "1,,3", "a,b,c", "1 2 3"}) {
    EXPECT_FALSE(ParsePose(bad, &p)) << bad;
  }
}

TEST(ToolArgumentsTest, PointsAreTwoCommaSeparatedNumbers) {
  Eigen::Vector2d p;
  ASSERT_TRUE(ParsePoint("1.5,-2", &p));
  EXPECT_EQ(p, Eigen::Vector2d(1.5, -2.0));
  for (const char* bad : {"", "1", "1,2,3", ",2", "1,", "x,2", "1;2"}) {
    EXPECT_FALSE(ParsePoint(bad, &p)) << bad;
  }
}

TEST(ToolArgumentsTest, SettingsAreKeyEqualsValueWithANonEmptyKey) {
  std::string key, value;
  ASSERT_TRUE(ParseSetting("map_resolution=0.05", &key, &value));
  EXPECT_EQ(key, "map_resolution");
  EXPECT_EQ(value, "0.05");
  ASSERT_TRUE(ParseSetting("lattice=", &key, &value));  // an empty value: the table refuses it
  EXPECT_EQ(value, "");
  ASSERT_TRUE(ParseSetting("a=b=c", &key, &value));
  EXPECT_EQ(value, "b=c");
  EXPECT_FALSE(ParseSetting("=1", &key, &value));
  EXPECT_FALSE(ParseSetting("novalue", &key, &value));
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
