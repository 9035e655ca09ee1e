#include "command_line.h"

#include <cstdio>

#include "hex_slam/logs/offline/tool_arguments.h"

namespace hex_slam {
namespace cli {
namespace {

// CLI11 reports a value a callback refused as "NAME: message".
[[noreturn]] void Refuse(const std::string& name, const std::string& message) {
  throw CLI::ValidationError(name, message);
}

CLI::Option* AddPoseSetter(CLI::App* app, const std::string& name,
                           const std::function<void(const Pose2&)>& set,
                           const std::string& description, const PoseCheck& check) {
  return app
      ->add_option_function<std::string>(
          name,
          [name, set, check](const std::string& text) {
            Pose2 pose;
            if (!logs::ParsePose(text, &pose)) {
              Refuse(name, "takes x,y,yaw (m, m, rad), got '" + text + "'");
            }
            const std::string error = check ? check(pose, name) : "";
            if (!error.empty()) throw CLI::ValidationError(error);
            set(pose);
          },
          description)
      ->type_name("x,y,yaw");
}

// A finite number; `check` returns what is wrong with one read whole (empty: nothing).
CLI::Option* AddCheckedNumber(CLI::App* app, const std::string& name, double* value,
                              const std::string& description,
                              const std::function<std::string(double)>& check) {
  return app
      ->add_option_function<std::string>(
          name,
          [name, value, check](const std::string& text) {
            double v = 0.0;
            if (!logs::ParseNumber(text, &v)) {
              Refuse(name, "takes a finite number, got '" + text + "'");
            }
            const std::string error = check(v);
            if (!error.empty()) Refuse(name, error + ", got '" + text + "'");
            *value = v;
          },
          description)
      ->type_name("NUMBER");
}

}  // namespace

std::optional<int> ParseCommandLine(const std::string& name, int argc, char** argv,
                                    const std::function<void(CLI::App*)>& declare,
                                    const std::function<std::string()>& check) {
  CLI::App app("", name);
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  declare(&app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return 0;
  } catch (const CLI::ParseError& e) {
    return UsageError(name, e.what());
  }
  const std::string error = check ? check() : "";
  if (!error.empty()) return UsageError(name, error);
  return std::nullopt;
}

std::string ShownNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

int UsageError(const std::string& name, const std::string& message) {
  std::fprintf(stderr, "error: %s\nRun %s --help for the usage.\n", message.c_str(),
               name.c_str());
  return kUsageError;
}

const CLI::Validator& NonEmpty() {
  static const CLI::Validator validator(
      [](std::string& value) {
        return value.empty() ? std::string("needs a value, got an empty one") : std::string();
      },
      "", "NonEmpty");
  return validator;
}

const CLI::Validator& NonNegative() {
  static const CLI::Validator validator(
      [](std::string& value) {
        return !value.empty() && value[0] == '-' ? "must not be negative, got '" + value + "'"
                                                 : std::string();
      },
      "", "NonNegative");
  return validator;
}

CLI::Option* AddPose(CLI::App* app, const std::string& name, Pose2* pose,
                     const std::string& description, const PoseCheck& check) {
  return AddPoseSetter(app, name, [pose](const Pose2& p) { *pose = p; }, description, check);
}

CLI::Option* AddOptionalPose(CLI::App* app, const std::string& name, std::optional<Pose2>* pose,
                             const std::string& description, const PoseCheck& check) {
  return AddPoseSetter(app, name, [pose](const Pose2& p) { *pose = p; }, description, check);
}

CLI::Option* AddPoint(CLI::App* app, const std::string& name, Eigen::Vector2d* point,
                      const std::string& description) {
  return app
      ->add_option_function<std::string>(
          name,
          [name, point](const std::string& text) {
            if (!logs::ParsePoint(text, point)) Refuse(name, "takes x,y (m), got '" + text + "'");
          },
          description)
      ->type_name("x,y");
}

CLI::Option* AddNumber(CLI::App* app, const std::string& name, double* value,
                       const std::string& description, std::optional<double> min) {
  return AddCheckedNumber(app, name, value, description, [min](double v) {
    return min && v < *min ? "must be at least " + ShownNumber(*min) : std::string();
  });
}

CLI::Option* AddPositiveNumber(CLI::App* app, const std::string& name, double* value,
                               const std::string& description) {
  return AddCheckedNumber(app, name, value, description, [](double v) {
    return v > 0.0 ? std::string() : std::string("must be above 0");
  });
}

CLI::Option* AddSettings(CLI::App* app, const std::string& name,
                         std::map<std::string, std::string>* settings,
                         const std::string& description) {
  return app
      ->add_option_function<std::vector<std::string>>(
          name,
          [name, settings](const std::vector<std::string>& texts) {
            for (const std::string& text : texts) {
              std::string key, value;
              if (!logs::ParseSetting(text, &key, &value)) {
                Refuse(name, "takes key=value, got '" + text + "'");
              }
              (*settings)[key] = value;
            }
          },
          description)
      ->type_name("KEY=VALUE")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
}

}  // namespace cli
}  // namespace hex_slam
