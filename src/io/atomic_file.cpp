#include "hex_slam/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace hex_slam {
namespace io {
namespace {

// fsync so a power cut after the rename cannot leave an empty file under the final name.
bool SyncFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

std::string WriteFileAtomically(const std::string& path,
                                const std::function<void(std::ostream&)>& write) {
  const std::string temp = path + ".tmp." + std::to_string(::getpid());
  std::string error;
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return "cannot create " + temp + ": " + std::strerror(errno);
    try {
      write(out);
    } catch (const std::exception& e) {
      error = std::string("while writing ") + path + ": " + e.what();
    }
    out.flush();
    if (error.empty() && !out) error = "write to " + temp + " failed (disk full?)";
  }
  if (error.empty() && !SyncFile(temp)) error = "cannot sync " + temp;
  if (error.empty() && std::rename(temp.c_str(), path.c_str()) != 0) {
    error = "cannot rename " + temp + " to " + path + ": " + std::strerror(errno);
  }
  if (!error.empty()) std::remove(temp.c_str());
  return error;
}

}  // namespace io
}  // namespace hex_slam
