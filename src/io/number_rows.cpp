#include "hex_slam/io/number_rows.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "hex_slam/io/bounded_line.h"

namespace hex_slam {
namespace io {
namespace {

// A record is a few numbers; a longer line is not one of these files.
constexpr std::size_t kMaxNumberRowBytes = 1 << 16;

}  // namespace

std::string ReadNumberRows(const std::string& path, int columns, const std::string& layout,
                           const std::function<std::string(const double* values)>& row) {
  std::ifstream in(path);
  if (!in) return "cannot read " + path;
  std::vector<double> values(columns);
  std::string line;
  long number = 0;
  for (;;) {
    const LineStatus status = ReadBoundedLine(in, kMaxNumberRowBytes, &line);
    if (status == LineStatus::kEnd) break;
    ++number;
    if (status == LineStatus::kTooLong) return LineTooLongMessage(path, number, kMaxNumberRowBytes);
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    bool ok = true;
    for (double& v : values) ok = ok && (fields >> v) && std::isfinite(v);
    if (!ok) {
      return path + ":" + std::to_string(number) + ": expected " + std::to_string(columns) +
             " finite numbers (" + layout + ")";
    }
    const std::string error = row(values.data());
    if (!error.empty()) return path + ":" + std::to_string(number) + ": " + error;
  }
  if (in.bad()) return path + ": read error after line " + std::to_string(number);
  return "";
}

}  // namespace io
}  // namespace hex_slam
