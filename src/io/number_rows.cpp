#include "hex_slam/io/number_rows.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

namespace hex_slam {
namespace io {

std::string ReadNumberRows(const std::string& path, int columns, const std::string& layout,
                           const std::function<void(const double* values)>& row) {
  std::ifstream in(path);
  if (!in) return "cannot read " + path;
  std::vector<double> values(columns);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    bool ok = true;
    for (double& v : values) ok = ok && (fields >> v) && std::isfinite(v);
    if (!ok) {
      return path + ":" + std::to_string(number) + ": expected " + std::to_string(columns) +
             " finite numbers (" + layout + ")";
    }
    row(values.data());
  }
  if (in.bad()) return path + ": read error after line " + std::to_string(number);
  return "";
}

}  // namespace io
}  // namespace hex_slam
