#include "hex_slam/io/parameter_file.h"

#include <yaml-cpp/yaml.h>

namespace hex_slam {
namespace io {

std::string ReadParameterFile(const std::string& path,
                              std::map<std::string, std::string>* values) {
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    return "cannot read parameter file " + path;
  } catch (const YAML::Exception& e) {
    return path + ": " + e.what();
  }
  if (doc.IsNull()) return "";  // an empty file sets nothing
  if (!doc.IsMap()) return path + ": expected a mapping of parameter names to values";
  for (const auto& entry : doc) {
    const std::string key = entry.first.as<std::string>();
    if (!entry.second.IsScalar()) return path + ": parameter '" + key + "' is not a single value";
    (*values)[key] = entry.second.as<std::string>();
  }
  return "";
}

}  // namespace io
}  // namespace hex_slam
