// The tools' command lines, on CLI11: the option kinds every tool shares, each checked the same
// way (a number must be finite and the whole text, a pose is x,y,yaw, a value is never empty), and
// what a usage error does: the message and a pointer to --help on stderr, exit status 2. --help
// prints the usage on stdout and exits 0.
#ifndef HEX_SLAM_SRC_TOOLS_COMMAND_LINE_H_
#define HEX_SLAM_SRC_TOOLS_COMMAND_LINE_H_

#include <functional>
#include <map>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace cli {

constexpr int kUsageError = 2;

// Parses `argv` for the tool `name`: `declare` adds its options to the app, and `check`, if
// given, judges the values together once they are parsed (empty: fine). An option given twice
// keeps its last value, as a default a script gives before the user's words expects
// (scripts/demo gives --out); --set keeps every one. Returns nothing when the tool goes on, else
// the status it exits with.
std::optional<int> ParseCommandLine(const std::string& name, int argc, char** argv,
                                    const std::function<void(CLI::App*)>& declare,
                                    const std::function<std::string()>& check = nullptr);
// Reports a usage error found outside ParseCommandLine. Returns kUsageError.
int UsageError(const std::string& name, const std::string& message);

// A number as a person writes it, for messages and --help: 10, not CLI11's 10.000000.
std::string ShownNumber(double value);

// Refuses an empty value ("--out ''"), which would otherwise name the current folder.
const CLI::Validator& NonEmpty();
// Refuses a negative count without CLI::NonNegativeNumber's bounds, printed as doubles.
const CLI::Validator& NonNegative();

// Options whose values CLI11 has no type for, or reads too leniently. Each refuses a value it
// cannot read whole, naming the option and what it takes; `check`, if given, returns an error
// for a pose read but out of range (common/input_limits.h).
using PoseCheck = std::function<std::string(const Pose2&, const std::string& option)>;
CLI::Option* AddPose(CLI::App* app, const std::string& name, Pose2* pose,
                     const std::string& description, const PoseCheck& check = nullptr);
CLI::Option* AddOptionalPose(CLI::App* app, const std::string& name, std::optional<Pose2>* pose,
                             const std::string& description, const PoseCheck& check = nullptr);
CLI::Option* AddPoint(CLI::App* app, const std::string& name, Eigen::Vector2d* point,
                      const std::string& description);
// A finite number (CLI11 would take "nan" and "inf"), optionally at least `min`.
CLI::Option* AddNumber(CLI::App* app, const std::string& name, double* value,
                       const std::string& description,
                       std::optional<double> min = std::nullopt);
// A finite number above 0 (a rate, a range, a duration).
CLI::Option* AddPositiveNumber(CLI::App* app, const std::string& name, double* value,
                               const std::string& description);
// --set key=value, repeatable; a later one for the same key wins.
CLI::Option* AddSettings(CLI::App* app, const std::string& name,
                         std::map<std::string, std::string>* settings,
                         const std::string& description);

}  // namespace cli
}  // namespace hex_slam

#endif  // HEX_SLAM_SRC_TOOLS_COMMAND_LINE_H_
