// Text files of whitespace-separated numbers, one record per line, '#' comments and blank lines
// skipped: the shape of TUM trajectories and of the Freiburg relations.
#ifndef HEX_SLAM_IO_NUMBER_ROWS_H_
#define HEX_SLAM_IO_NUMBER_ROWS_H_

#include <functional>
#include <string>

namespace hex_slam {
namespace io {

// Calls `row` with the first `columns` numbers of each record, all finite (extra fields are
// ignored); `row` returns an empty string or what is wrong with the record (a value out of
// bounds). Returns an empty string, or an error naming the file and line (an unreadable file, a
// line longer than 64 KiB, a record with fewer numbers or a non-finite one, `row`'s error);
// `layout` names the columns in that message.
std::string ReadNumberRows(const std::string& path, int columns, const std::string& layout,
                           const std::function<std::string(const double* values)>& row);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_NUMBER_ROWS_H_
