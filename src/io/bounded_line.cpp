#include "hex_slam/io/bounded_line.h"

namespace hex_slam {
namespace io {

LineStatus ReadBoundedLine(std::istream& in, std::size_t max_bytes, std::string* line) {
  line->clear();
  std::streambuf* buffer = in.rdbuf();
  if (!in.good() || buffer == nullptr) return LineStatus::kEnd;
  bool read_any = false;
  for (;;) {
    const std::streambuf::int_type c = buffer->sbumpc();
    if (std::streambuf::traits_type::eq_int_type(c, std::streambuf::traits_type::eof())) {
      in.setstate(std::ios::eofbit);
      return read_any ? LineStatus::kLine : LineStatus::kEnd;
    }
    read_any = true;
    const char ch = std::streambuf::traits_type::to_char_type(c);
    if (ch == '\n') return LineStatus::kLine;
    if (line->size() >= max_bytes) return LineStatus::kTooLong;
    line->push_back(ch);
  }
}

std::string LineTooLongMessage(const std::string& name, long number, std::size_t max_bytes) {
  return name + ":" + std::to_string(number) + ": line is longer than " +
         std::to_string(max_bytes) + " bytes (not a text file?)";
}

}  // namespace io
}  // namespace hex_slam
