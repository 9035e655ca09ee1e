#include "hex_slam/io/parameter_file.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <iterator>

namespace hex_slam {
namespace io {
namespace {

// A parameter file is a few kilobytes; a larger one (or /dev/zero) is not read into memory.
constexpr std::size_t kMaxParameterFileBytes = std::size_t{1} << 20;

}  // namespace

std::string ReadParameterFile(const std::string& path,
                              std::map<std::string, std::string>* values) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot read parameter file " + path;
  std::string text(kMaxParameterFileBytes + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  if (in.bad()) return "cannot read parameter file " + path;
  if (static_cast<std::size_t>(in.gcount()) > kMaxParameterFileBytes) {
    return path + ": larger than " + std::to_string(kMaxParameterFileBytes) +
           " bytes, not a parameter file";
  }
  text.resize(static_cast<std::size_t>(in.gcount()));
  return ParseParameterText(text, path, values);
}

std::string ParseParameterText(const std::string& text, const std::string& name,
                               std::map<std::string, std::string>* values) {
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return name + ": " + e.what();
  }
  if (doc.IsNull()) return "";  // an empty file sets nothing
  if (!doc.IsMap()) return name + ": expected a mapping of parameter names to values";
  for (const auto& entry : doc) {
    if (!entry.first.IsScalar()) return name + ": a parameter name is not a single word";
    const std::string key = entry.first.as<std::string>();
    if (!entry.second.IsScalar()) return name + ": parameter '" + key + "' is not a single value";
    (*values)[key] = entry.second.as<std::string>();
  }
  return "";
}

}  // namespace io
}  // namespace hex_slam
