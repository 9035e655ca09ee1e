// libFuzzer target: the parameters hex_slam_offline reads, as it reads them: a YAML parameter file
// (the node's flat format), then after a NUL byte one --set key=value per line. Options that
// validate must make a SLAM processor without an exception.
#include <cstddef>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "hex_slam/io/parameter_file.h"
#include "hex_slam/logs/offline/offline_config.h"
#include "hex_slam/logs/offline/tool_arguments.h"
#include "hex_slam/mapping/slam.h"

namespace {

// Larger initial maps are validated but not built: a valid map_size of 10^4 allocates gigabytes.
constexpr int kMaxBuiltMapSize = 128;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hex_slam;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  std::map<std::string, std::string> values;
  if (!io::ParseParameterText(input.substr(0, split), "fuzz", &values).empty()) return 0;
  if (split != std::string::npos) {
    std::istringstream lines(input.substr(split + 1));
    std::string line, key, value;
    while (std::getline(lines, line)) {
      if (logs::ParseSetting(line, &key, &value)) values[key] = value;
    }
  }
  logs::OfflineConfig config;
  std::vector<std::string> ignored;
  std::vector<std::string> errors = logs::ApplyOfflineParameters(values, &config, &ignored);
  for (const std::string& e : config.slam.Validate()) errors.push_back(e);
  if (!errors.empty() || config.slam.map_size > kMaxBuiltMapSize) return 0;
  Slam slam(config.slam);  // throws, and so aborts the fuzzer, if Validate missed something
  return 0;
}
