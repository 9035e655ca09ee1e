#include "hex_slam/logs/carmen_reader.h"

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "hex_slam/logs/stamp_order.h"
#include "test_data.h"

namespace hex_slam {
namespace logs {
namespace {

std::string Repeat(const std::string& word, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += word + " ";
  return s;
}

std::string Parse(const std::string& text, CarmenLog* log,
                  const CarmenReadOptions& options = CarmenReadOptions()) {
  std::istringstream in(text);
  return ParseCarmenLog(in, "test.clf", options, log);
}

TEST(CarmenReaderTest, FlaserFanOdometryMountingAndNoReturns) {
  // 180 beams, the SICK "no return" value in beam 3, the laser 0.1 m ahead of a base turned 90°.
  const std::string line = "FLASER 180 1.5 2.5 81.83 " + Repeat("3.0", 177) +
                           "1.0 2.1 1.5707963 1.0 2.0 1.5707963 976052857.337530 nohost 0.000246\n";
  CarmenLog log;
  ASSERT_EQ(Parse("# header\nPARAM robot_length 0.5\n" + line, &log), "");
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.laser_message, "FLASER");
  EXPECT_EQ(log.other_lines, 2);
  const LogScan& s = log.scans[0];
  EXPECT_DOUBLE_EQ(s.scan.stamp, 976052857.337530);
  ASSERT_EQ(s.scan.ranges.size(), 180u);
  EXPECT_FLOAT_EQ(s.scan.ranges[0], 1.5f);
  EXPECT_TRUE(std::isinf(s.scan.ranges[2]));
  // 180 beams over 180° from -90°: 1° steps, the last at +89°.
  EXPECT_NEAR(s.scan.angle_min, -M_PI / 2, 1e-12);
  EXPECT_NEAR(s.scan.angle_increment, M_PI / 180, 1e-12);
  EXPECT_NEAR(s.scan.angle_max, 89.0 * M_PI / 180, 1e-12);
  ASSERT_TRUE(s.odometry.has_value());
  EXPECT_DOUBLE_EQ(s.odometry->y, 2.0);
  EXPECT_NEAR(s.sensor_pose.x, 0.1, 1e-6);  // +y in the world is ahead of this base
  EXPECT_NEAR(s.sensor_pose.y, 0.0, 1e-6);
  EXPECT_NEAR(s.sensor_pose.theta, 0.0, 1e-12);
}

TEST(CarmenReaderTest, OddBeamCountsIncludeBothEndsOfTheFan) {
  CarmenLog log;
  ASSERT_EQ(Parse("FLASER 181 " + Repeat("2", 181) + "0 0 0 0 0 0 5.0 h 5.0\n", &log), "");
  EXPECT_NEAR(log.scans[0].scan.angle_max, M_PI / 2, 1e-12);
  EXPECT_NEAR(log.scans[0].scan.angle_increment, M_PI / 180, 1e-12);
  // A laser logged exactly at the base's pose gets exactly the identity.
  EXPECT_EQ(log.scans[0].sensor_pose.x, 0.0);
}

TEST(CarmenReaderTest, RobotLaserGivesItsOwnGeometryAndSkipsRemissions) {
  // type start fov res max_range accuracy mode n r1..r4 m v1 v2 laser(3) robot(3) tv rv f s t
  const std::string line =
      "ROBOTLASER1 0 -1.0 2.0 0.5 10.0 0.01 0 4 1 2 12 4 2 0.5 0.6 "
      "0.2 0 0.1 0 0 0 0.3 0.1 0.5 0.5 0.2 100.25 host 100.2\n";
  CarmenLog log;
  ASSERT_EQ(Parse(line, &log), "");
  ASSERT_EQ(log.scans.size(), 1u);
  const LogScan& s = log.scans[0];
  EXPECT_DOUBLE_EQ(s.scan.angle_min, -1.0);
  EXPECT_DOUBLE_EQ(s.scan.angle_increment, 0.5);
  EXPECT_DOUBLE_EQ(s.scan.angle_max, 0.5);
  EXPECT_DOUBLE_EQ(s.scan.range_max, 10.0);
  EXPECT_TRUE(std::isinf(s.scan.ranges[2]));  // 12 m is beyond the laser's 10 m
  EXPECT_DOUBLE_EQ(s.scan.stamp, 100.25);
  EXPECT_NEAR(s.sensor_pose.x, 0.2, 1e-12);
  EXPECT_NEAR(s.sensor_pose.theta, 0.1, 1e-12);
}

TEST(CarmenReaderTest, RawLaserOdometryIsInterpolatedFromOdomLines) {
  const std::string raw = "RAWLASER1 0 -1.5 3.0 1.0 20 0.01 0 4 1 1 1 1 0 ";
  const std::string text = "ODOM 0 0 0 0 0 0 10.0 h 10.0\n" + raw + "10.25 h 10.25\n" +
                           "ODOM 1 0 0.4 0 0 0 11.0 h 11.0\n" + raw + "12.0 h 12.0\n";
  CarmenLog log;
  ASSERT_EQ(Parse(text, &log), "");
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.odometry_lines, 2);
  ASSERT_TRUE(log.scans[0].odometry.has_value());
  EXPECT_NEAR(log.scans[0].odometry->x, 0.25, 1e-12);
  EXPECT_NEAR(log.scans[0].odometry->theta, 0.1, 1e-12);
  // After the last ODOM line: the last odometry, not an extrapolation.
  EXPECT_NEAR(log.scans[1].odometry->x, 1.0, 1e-12);
}

TEST(CarmenReaderTest, OnlyOneLaserIsReadTheFirstOrTheNamedOne) {
  const std::string flaser = "FLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n";
  const std::string raw = "RAWLASER2 0 -1.5 3.0 1.0 20 0.01 0 4 1 1 1 1 0 2.0 h 2.0\n";
  CarmenLog log;
  ASSERT_EQ(Parse(flaser + raw + flaser, &log), "");
  EXPECT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.other_lines, 1);
  CarmenReadOptions options;
  options.laser_message = "RAWLASER2";
  ASSERT_EQ(Parse(flaser + raw + flaser, &log, options), "");
  EXPECT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.laser_message, "RAWLASER2");
  EXPECT_FALSE(log.scans[0].odometry.has_value());  // no ODOM lines at all
  options.laser_message = "RAWLASER3";
  EXPECT_NE(Parse(flaser, &log, options).find("no laser scans"), std::string::npos);
}

TEST(CarmenReaderTest, MalformedLinesAreErrorsNamingTheLine) {
  const std::string good = "FLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n";
  CarmenLog log;
  EXPECT_NE(Parse(good + "FLASER 3 1 1 1 0 0\n", &log).find("test.clf:2: FLASER line has"),
            std::string::npos);
  EXPECT_NE(Parse(good + good + "FLASER 3 1 x 1 0 0 0 0 0 0 1.0 h 1.0\n", &log).find(":3:"),
            std::string::npos);
  EXPECT_NE(Parse("FLASER 99999999 1\n", &log).find("not a count"), std::string::npos);
  EXPECT_NE(Parse("FLASER -3 1 1 1\n", &log).find("not a count"), std::string::npos);
  EXPECT_NE(Parse("FLASER 3 1 1 1 0 nan 0 0 0 0 1.0 h 1.0\n", &log).find("finite"),
            std::string::npos);
  EXPECT_NE(Parse("ODOM 1 2\n" + good, &log).find(":1: ODOM"), std::string::npos);
  EXPECT_NE(Parse("", &log).find("no laser scans"), std::string::npos);
}

TEST(CarmenReaderTest, SkipBadLinesKeepsTheRestAndCountsThem) {
  const std::string good = "FLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n";
  CarmenReadOptions options;
  options.skip_bad_lines = true;
  CarmenLog log;
  // A truncated last line, as a logger killed mid-write leaves.
  ASSERT_EQ(Parse(good + "FLASER 3 1 bad\n" + good + "FLASER 3 1 1", &log, options), "");
  EXPECT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.bad_lines, 2);
  EXPECT_NE(log.first_bad_line.find(":2:"), std::string::npos);
}

TEST(CarmenReaderTest, NanRangesStayNanForTheSanitizer) {
  CarmenLog log;
  ASSERT_EQ(Parse("FLASER 3 1 nan 1 0 0 0 0 0 0 1.0 h 1.0\n", &log), "");
  EXPECT_TRUE(std::isnan(log.scans[0].scan.ranges[1]));
}

// The first error of parsing `text` (one scan line, possibly after ODOM lines).
std::string ErrorOf(const std::string& text) {
  CarmenLog log;
  return Parse(text, &log);
}

TEST(CarmenReaderTest, TheDeclaredCountMustMatchTheReadings) {
  // Issue 12: "FLASER 180" carrying 190 readings was accepted, the extra ones read as pose,
  // odometry and stamp. Every message's fields after its last pose are ipc_timestamp and, at
  // most, hostname and logger_timestamp.
  const std::string tail = " 0 0 0 0 0 0 1.0 h 1.0\n";
  EXPECT_EQ(ErrorOf("FLASER 3 1 1 1" + tail), "");
  EXPECT_EQ(ErrorOf("FLASER 3 1 1 1 0 0 0 0 0 0 1.0\n"), "");  // hostname etc. dropped
  EXPECT_NE(ErrorOf("FLASER 3 1 1 1 1" + tail).find("test.clf:1: FLASER line has 15 fields, more "
                                                    "than 3 readings"),
            std::string::npos)
      << ErrorOf("FLASER 3 1 1 1 1" + tail);
  // One reading too many and no hostname: the stamp would land in the hostname's place.
  EXPECT_NE(ErrorOf("FLASER 3 1 1 1 1 0 0 0 0 0 0 1.0\n").find("does the count match"),
            std::string::npos);
  EXPECT_NE(ErrorOf("ODOM 0 0 0 0 0 0 1.0 h 1.0 extra\n").find("ODOM line has 11 fields"),
            std::string::npos);
  EXPECT_NE(ErrorOf("RAWLASER1 0 -1.5 3.0 1.0 20 0.01 0 2 1 1 0 1 2.0 h 2.0\n").find("more than"),
            std::string::npos);
  EXPECT_NE(ErrorOf("FLASER 3 1 1 1 0 0 0 0 0 0 1.0 h x\n").find("logger_timestamp"),
            std::string::npos);
}

TEST(CarmenReaderTest, PosesStampsAndMountingsOutsidePhysicalBoundsAreNamed) {
  const struct {
    std::string line;
    std::string says;
  } cases[] = {
      // Issue 12: a pose field >= 1e9 in one line crashed hex_slam_offline.
      {"FLASER 3 1 1 1 0 0 0 1e9 0 0 1.0 h 1.0", "FLASER robot pose: x = 1e+09 is beyond ±1e+07 m"},
      {"FLASER 3 1 1 1 0 -1e15 0 0 0 0 1.0 h 1.0", "FLASER laser pose: y = -1e+15"},
      {"FLASER 3 1 1 1 0 0 1e7 0 0 1e7 1.0 h 1.0", "yaw = 1e+07 is beyond ±1e+06 rad"},
      {"FLASER 3 1 1 1 0 0 0 0 0 0 -1.0 h 1.0", "stamp -1 s is outside ROS time"},
      {"FLASER 3 1 1 1 0 0 0 0 0 0 4294967296 h 1.0", "outside ROS time"},
      // A laser 65 km from its base: a bad calibration line.
      {"FLASER 3 1 1 1 65000 0 0 0 0 0 1.0 h 1.0", "the laser sits 65000 m from the base"},
      {"FLASER 3 1 -1 1 0 0 0 0 0 0 1.0 h 1.0", "reading 2 (-1) is negative"},
      {"ODOM 2e7 0 0 0 0 0 1.0 h 1.0", "ODOM pose: x = 2e+07"},
      {"ODOM 0 0 0 nan 0 0 1.0 h 1.0", "velocity"},
  };
  for (const auto& c : cases) {
    EXPECT_NE(ErrorOf(c.line + "\n").find(c.says), std::string::npos)
        << c.line << " -> " << ErrorOf(c.line + "\n");
  }
}

TEST(CarmenReaderTest, RobotAndRawLaserGeometryRemissionsAndVelocitiesAreChecked) {
  // type start fov res max_range accuracy mode n r1..r4 m v1 v2 laser(3) robot(3) tv rv f s t
  const std::string head = "ROBOTLASER1 0 -1.0 2.0 0.5 10.0 0.01 0 4 1 2 12 4 2 ";
  const std::string poses = "0.2 0 0.1 0 0 0 ";
  const std::string rest = "0.3 0.1 0.5 0.5 0.2 100.25 host 100.2\n";
  EXPECT_EQ(ErrorOf(head + "0.5 0.6 " + poses + rest), "");
  EXPECT_NE(ErrorOf(head + "0.5 x " + poses + rest).find("remission 2 is not a finite number"),
            std::string::npos);
  EXPECT_NE(ErrorOf(head + "0.5 0.6 " + poses + "0.3 nan 0.5 0.5 0.2 100.25 host 100.2\n")
                .find("velocity"),
            std::string::npos);
  EXPECT_NE(ErrorOf("ROBOTLASER1 0 -1.0 2.0 0.5 1e30 0.01 0 4 1 2 12 4 2 0.5 0.6 " + poses + rest)
                .find("maximum range in (0, 10000] m"),
            std::string::npos);
  EXPECT_NE(ErrorOf("ROBOTLASER1 0 -1.0 200 0.5 10 0.01 0 4 1 2 12 4 2 0.5 0.6 " + poses + rest)
                .find("beyond a full turn"),
            std::string::npos);
  EXPECT_NE(ErrorOf("RAWLASER1 0 -1.5 3.0 1.0 20 0.01 0 4 1 1 1 1 0 1e10 h 2.0\n")
                .find("outside ROS time"),
            std::string::npos);
}

TEST(CarmenReaderTest, ALineWithoutEndIsRefusedAtTheCapNotReadIntoMemory) {
  // Issue 12: --carmen /dev/zero grew without bound. The cap is 4 MiB, far above the longest real
  // line (65,536 readings and remissions).
  std::istringstream in(std::string(5 << 20, '\0'));
  CarmenLog log;
  EXPECT_EQ(ParseCarmenLog(in, "zero", CarmenReadOptions(), &log),
            "zero:1: line is longer than 4194304 bytes (not a text file?)");
  CarmenReadOptions skip;
  skip.skip_bad_lines = true;  // not even then: the rest of such a file is no log either
  std::istringstream again(std::string(5 << 20, 'x'));
  EXPECT_NE(ParseCarmenLog(again, "x", skip, &log).find("line is longer"), std::string::npos);
}

TEST(CarmenReaderTest, MissingFileIsAnError) {
  CarmenLog log;
  EXPECT_NE(ReadCarmenLog("/nonexistent/x.clf", CarmenReadOptions(), &log).find("cannot read"),
            std::string::npos);
}

TEST(CarmenReaderTest, TheIntelSubsetHas5505ScansAnd265BackwardStamps) {
  const std::string path = test::DataFile(test::kIntelLog);
  HEX_SLAM_REQUIRE_DATA(path);
  CarmenLog log;
  ASSERT_EQ(ReadCarmenLog(path, CarmenReadOptions(), &log), "");
  ASSERT_EQ(log.scans.size(), 5505u);
  std::vector<double> stamps;
  for (const LogScan& s : log.scans) stamps.push_back(s.scan.stamp);
  EXPECT_EQ(CountBackwardSteps(stamps), 265);  // kept as logged
  EXPECT_EQ(log.scans[0].scan.ranges.size(), 180u);
  EXPECT_EQ(log.scans[0].sensor_pose.x, 0.0);
  EXPECT_NEAR(stamps.back() - stamps.front(), 1088.6, 0.1);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
