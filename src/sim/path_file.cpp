#include "hex_slam/sim/path_file.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iomanip>
#include <set>

#include "hex_slam/io/atomic_file.h"

namespace hex_slam {
namespace sim {

std::string ReadWaypointPath(const std::string& path, WaypointPath* out) {
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    return path + ": " + e.what();
  }
  if (!doc.IsMap()) return path + ": not a YAML mapping";
  const std::set<std::string> known = {"format", "version", "start_heading", "waypoints"};
  for (const auto& entry : doc) {
    const std::string key = entry.first.as<std::string>("");
    if (!known.count(key)) return path + ": unknown key '" + key + "'";
  }
  WaypointPath result;
  try {
    if (!doc["format"] || doc["format"].as<std::string>() != kWaypointPathFormat) {
      return path + ": 'format' must be " + kWaypointPathFormat;
    }
    if (!doc["version"] || doc["version"].as<int>() != kWaypointPathVersion) {
      return path + ": unsupported 'version' (this reader knows version " +
             std::to_string(kWaypointPathVersion) + ")";
    }
    if (doc["start_heading"]) result.start_heading = doc["start_heading"].as<double>();
  } catch (const YAML::Exception&) {
    return path + ": 'format', 'version' or 'start_heading' has a bad value";
  }
  if (!std::isfinite(result.start_heading)) return path + ": 'start_heading' is not finite";
  const YAML::Node list = doc["waypoints"];
  if (!list || !list.IsSequence() || list.size() == 0) {
    return path + ": 'waypoints' must be a non-empty list of [x, y]";
  }
  if (list.size() > static_cast<std::size_t>(kMaxWaypoints)) {
    return path + ": more than " + std::to_string(kMaxWaypoints) + " waypoints";
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = path + ": waypoint " + std::to_string(i);
    if (!list[i].IsSequence() || list[i].size() != 2) return where + " is not [x, y]";
    Eigen::Vector2d p;
    try {
      p = {list[i][0].as<double>(), list[i][1].as<double>()};
    } catch (const YAML::Exception&) {
      return where + " is not two numbers";
    }
    if (!p.allFinite()) return where + " is not finite";
    result.waypoints.push_back(p);
  }
  *out = std::move(result);
  return "";
}

std::string WriteWaypointPath(const std::string& path, const WaypointPath& waypoints) {
  if (waypoints.waypoints.empty()) return path + ": a path needs at least one waypoint";
  return io::WriteFileAtomically(path, [&](std::ostream& out) {
    out << std::setprecision(10);
    out << "format: " << kWaypointPathFormat << "\nversion: " << kWaypointPathVersion
        << "\nstart_heading: " << waypoints.start_heading << "\nwaypoints:\n";
    for (const Eigen::Vector2d& p : waypoints.waypoints) {
      out << "  - [" << p.x() << ", " << p.y() << "]\n";
    }
  });
}

}  // namespace sim
}  // namespace hex_slam
