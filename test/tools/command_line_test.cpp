// The option kinds the tools share (src/tools/command_line.h), parsed as a user would type them.
#include "command_line.h"

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/common/input_limits.h"

namespace hex_slam {
namespace {

struct Parsed {
  std::optional<int> status;  // nothing: the tool goes on
  double number = 1.0;
  double rate = 1.0;
  Pose2 pose;
  std::optional<Pose2> mount;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  std::string out = "unset";
  std::map<std::string, std::string> settings;
};

Parsed ParseWords(std::vector<std::string> words,
                  const std::function<std::string(const Parsed&)>& check = nullptr) {
  words.insert(words.begin(), "tool");
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  Parsed p;
  p.status = cli::ParseCommandLine(
      "tool", static_cast<int>(argv.size()), argv.data(),
      [&p](CLI::App* app) {
        cli::AddNumber(app, "--number", &p.number, "", 0.0);
        cli::AddPositiveNumber(app, "--rate", &p.rate, "");
        cli::AddPose(app, "--pose", &p.pose, "");
        cli::AddOptionalPose(app, "--mount", &p.mount, "", CheckSensorPose);
        cli::AddPoint(app, "--point", &p.point, "");
        app->add_option("--out", p.out, "")->check(cli::NonEmpty());
        cli::AddSettings(app, "--set", &p.settings, "");
      },
      check ? [&p, &check] { return check(p); } : std::function<std::string()>());
  return p;
}

TEST(CommandLineTest, GoodValuesAreReadWhole) {
  const Parsed p = ParseWords({"--number", "0.5", "--rate", "10", "--pose", "1,-2,0.3", "--mount",
                               "0.1,0,0", "--point", "4,5", "--out", "d", "--set", "a=1", "--set",
                               "b=x=y"});
  EXPECT_FALSE(p.status);
  EXPECT_EQ(p.number, 0.5);
  EXPECT_EQ(p.rate, 10.0);
  EXPECT_EQ(p.pose.y, -2.0);
  ASSERT_TRUE(p.mount);
  EXPECT_EQ(p.mount->x, 0.1);
  EXPECT_EQ(p.point, Eigen::Vector2d(4, 5));
  EXPECT_EQ(p.out, "d");
  EXPECT_EQ(p.settings, (std::map<std::string, std::string>{{"a", "1"}, {"b", "x=y"}}));
}

TEST(CommandLineTest, AnOptionGivenTwiceKeepsTheLastValueButEverySettingIsKept) {
  const Parsed p = ParseWords({"--out", "a", "--out", "b", "--set", "k=1", "--set", "k=2"});
  EXPECT_FALSE(p.status);
  EXPECT_EQ(p.out, "b");
  EXPECT_EQ(p.settings.at("k"), "2");
}

TEST(CommandLineTest, EveryBadValueIsAUsageError) {
  for (const std::vector<std::string>& words : std::vector<std::vector<std::string>>{
           {"--number", "nan"}, {"--number", "inf"}, {"--number", "0.5m"}, {"--number", "-1"},
           {"--rate", "0"}, {"--rate", "-3"}, {"--pose", "1,2"}, {"--pose", "1,2,3,4"},
           {"--mount", "500,0,0"}, {"--point", "1"}, {"--out", ""}, {"--set", "novalue"},
           {"--out"}, {"--frobnicate"}}) {
    std::string joined;
    for (const std::string& w : words) joined += w + " ";
    const Parsed p = ParseWords(words);
    ASSERT_TRUE(p.status) << joined;
    EXPECT_EQ(*p.status, cli::kUsageError) << joined;
    EXPECT_EQ(p.number, 1.0) << joined;  // nothing half-read
  }
}

TEST(CommandLineTest, HelpExitsZeroAndALaterCheckIsAUsageError) {
  EXPECT_EQ(ParseWords({"--help"}).status, std::optional<int>(0));
  const Parsed refused = ParseWords({"--number", "3"}, [](const Parsed& p) {
    return p.number > 2.0 ? std::string("--number must not exceed 2") : std::string();
  });
  EXPECT_EQ(refused.status, std::optional<int>(cli::kUsageError));
}

}  // namespace
}  // namespace hex_slam
