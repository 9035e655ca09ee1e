// Writing files so that a reader never sees half of one: write a temporary file beside the
// target, flush it to disk, then rename it over the target (atomic on POSIX file systems).
#ifndef HEX_SLAM_IO_ATOMIC_FILE_H_
#define HEX_SLAM_IO_ATOMIC_FILE_H_

#include <functional>
#include <ostream>
#include <string>

namespace hex_slam {
namespace io {

// Calls `write` with a stream to a temporary file, then renames it to `path`. Returns an empty
// string on success; otherwise an error message, and neither `path` nor a temporary is left
// changed or behind. A `write` that throws or leaves the stream failed counts as an error.
std::string WriteFileAtomically(const std::string& path,
                                const std::function<void(std::ostream&)>& write);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_ATOMIC_FILE_H_
