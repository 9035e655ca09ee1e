#include "hex_slam/io/map_server_io.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "hex_slam/io/atomic_file.h"
#include "hex_slam/io/image_io.h"

namespace hex_slam {
namespace io {
namespace {

std::string Basename(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string Directory(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

template <class T>
bool Read(const YAML::Node& node, const char* key, T* out, std::string* error) {
  if (!node[key]) {
    *error = std::string("missing key '") + key + "'";
    return false;
  }
  try {
    *out = node[key].as<T>();
  } catch (const YAML::Exception&) {
    *error = std::string("bad value for '") + key + "'";
    return false;
  }
  return true;
}

}  // namespace

std::string SaveMapServerMap(const OccupancyRaster& raster, const std::string& base) {
  AtomicFileSet files;
  AddMapServerMap(raster, base, &files);
  return files.Commit();
}

void AddMapServerMap(const OccupancyRaster& raster, const std::string& base, AtomicFileSet* files) {
  Image image(raster.width, raster.height, 1);
  for (int row = 0; row < raster.height; ++row) {
    for (int col = 0; col < raster.width; ++col) {
      const int value = raster.at(col, row);
      const int gray = value == OccupancyRaster::kUnknown ? MapServerFormat::kUnknownGray
                       : value >= 65                      ? MapServerFormat::kOccupiedGray
                       : value <= 25                      ? MapServerFormat::kFreeGray
                                                          : MapServerFormat::kUnknownGray;
      *image.at(col, raster.height - 1 - row) = static_cast<std::uint8_t>(gray);  // top row first
    }
  }
  const std::string pgm = base + ".pgm";
  AddPgm(pgm, image, files);
  const MapServerFormat format;
  files->Add(base + ".yaml", [&](std::ostream& out) {
    out << std::fixed << std::setprecision(6);
    out << "image: " << Basename(pgm) << "\n"
        << "resolution: " << raster.resolution << "\n"
        << "origin: [" << raster.origin.x() << ", " << raster.origin.y() << ", 0.000000]\n"
        << "negate: 0\n"
        << "occupied_thresh: " << format.occupied_thresh << "\n"
        << "free_thresh: " << format.free_thresh << "\n";
  });
}

std::string LoadMapServerMap(const std::string& yaml_path, OccupancyRaster* raster) {
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(yaml_path);
  } catch (const YAML::Exception& e) {
    return yaml_path + ": " + e.what();
  }
  if (!doc.IsMap()) return yaml_path + ": not a YAML mapping";
  std::string error, image_name, mode = "trinary";
  double resolution = 0.0, occupied = 0.0, free = 0.0;
  int negate = 0;
  std::vector<double> origin;
  if (!Read(doc, "image", &image_name, &error) || !Read(doc, "resolution", &resolution, &error) ||
      !Read(doc, "origin", &origin, &error) || !Read(doc, "negate", &negate, &error) ||
      !Read(doc, "occupied_thresh", &occupied, &error) ||
      !Read(doc, "free_thresh", &free, &error)) {
    return yaml_path + ": " + error;
  }
  if (doc["mode"] && !Read(doc, "mode", &mode, &error)) return yaml_path + ": " + error;
  if (!(resolution > 0.0) || !std::isfinite(resolution)) return yaml_path + ": resolution <= 0";
  if (origin.size() != 3) return yaml_path + ": origin must be [x, y, yaw]";
  if (std::abs(origin[2]) > 1e-9) return yaml_path + ": rotated map origins are not supported";
  if (mode != "trinary" && mode != "scale" && mode != "raw") {
    return yaml_path + ": unknown mode '" + mode + "'";
  }
  const std::string image_path =
      image_name.empty() || image_name[0] == '/' ? image_name : Directory(yaml_path) + "/" + image_name;
  Image image;
  error = ReadGrayImage(image_path, &image);
  if (!error.empty()) return error;

  raster->resolution = resolution;
  raster->origin = Eigen::Vector2d(origin[0], origin[1]);
  raster->width = image.width;
  raster->height = image.height;
  raster->data.assign(image.pixels.size(), OccupancyRaster::kUnknown);
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const int gray = *image.at(col, image.height - 1 - row);
      std::int8_t& value = raster->data[static_cast<std::size_t>(row) * image.width + col];
      if (mode == "raw") {
        value = static_cast<std::int8_t>(std::min(gray, 100));
        continue;
      }
      const double p = negate ? gray / 255.0 : (255.0 - gray) / 255.0;
      if (p > occupied) {
        value = OccupancyRaster::kOccupied;
      } else if (p < free) {
        value = OccupancyRaster::kFree;
      } else if (mode == "scale") {
        value = static_cast<std::int8_t>(99.0 * (p - free) / (occupied - free));
      }
    }
  }
  return "";
}

}  // namespace io
}  // namespace hex_slam
