// Reading text one line at a time with a cap on the line's length, so a file without newlines
// (/dev/zero, a binary file given by mistake, a corrupt log) is an error after the cap instead of
// a string that grows until memory runs out, as std::getline's would.
#ifndef HEX_SLAM_IO_BOUNDED_LINE_H_
#define HEX_SLAM_IO_BOUNDED_LINE_H_

#include <cstddef>
#include <istream>
#include <string>

namespace hex_slam {
namespace io {

enum class LineStatus {
  kLine,     // `line` holds the next line, without its '\n'
  kEnd,      // no more lines
  kTooLong,  // the line exceeds the cap; `line` holds its first max_bytes bytes
};

LineStatus ReadBoundedLine(std::istream& in, std::size_t max_bytes, std::string* line);

// "name:N: line is longer than M bytes (not a text file?)".
std::string LineTooLongMessage(const std::string& name, long number, std::size_t max_bytes);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_BOUNDED_LINE_H_
