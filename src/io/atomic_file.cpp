#include "hex_slam/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
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

bool IsDirectory(const std::string& path) {
  struct stat s;
  return ::stat(path.c_str(), &s) == 0 && S_ISDIR(s.st_mode);
}

bool Exists(const std::string& path) {
  struct stat s;
  return ::lstat(path.c_str(), &s) == 0;
}

std::string Suffix() { return "." + std::to_string(::getpid()); }

}  // namespace

AtomicFileSet::~AtomicFileSet() {
  if (!committed_) RemoveTemporaries();
}

void AtomicFileSet::RemoveTemporaries() {
  for (const Pending& p : pending_) std::remove(p.temp.c_str());
  pending_.clear();
}

void AtomicFileSet::Fail(const std::string& error) {
  if (error_.empty()) error_ = error;
}

void AtomicFileSet::Add(const std::string& path,
                        const std::function<void(std::ostream&)>& write) {
  if (!error_.empty()) return;
  const std::string temp = path + ".tmp" + Suffix();
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) {
      error_ = "cannot create " + temp + ": " + std::strerror(errno);
      return;
    }
    pending_.push_back({path, temp});
    try {
      write(out);
    } catch (const std::exception& e) {
      error_ = std::string("while writing ") + path + ": " + e.what();
    }
    out.flush();
    if (error_.empty() && !out) error_ = "write to " + temp + " failed (disk full?)";
  }
  if (error_.empty() && !SyncFile(temp)) error_ = "cannot sync " + temp;
}

std::string AtomicFileSet::Commit() {
  committed_ = true;
  for (const Pending& p : pending_) {
    if (error_.empty() && IsDirectory(p.path)) error_ = "cannot write " + p.path + ": a directory";
  }
  if (!error_.empty()) {
    RemoveTemporaries();
    return error_;
  }
  // A hard link keeps each replaced file's old contents until every rename has succeeded.
  std::vector<std::string> backups(pending_.size());
  std::size_t renamed = 0;
  for (; renamed < pending_.size(); ++renamed) {
    const Pending& p = pending_[renamed];
    if (Exists(p.path)) {
      const std::string backup = p.path + ".old" + Suffix();
      if (::link(p.path.c_str(), backup.c_str()) == 0) backups[renamed] = backup;
    }
    if (std::rename(p.temp.c_str(), p.path.c_str()) != 0) {
      error_ = "cannot rename " + p.temp + " to " + p.path + ": " + std::strerror(errno);
      break;
    }
  }
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (!error_.empty() && i < renamed) {
      // Undo: the previous contents back, or the new file gone.
      if (!backups[i].empty()) {
        std::rename(backups[i].c_str(), pending_[i].path.c_str());
      } else {
        std::remove(pending_[i].path.c_str());
      }
    } else if (!backups[i].empty()) {
      std::remove(backups[i].c_str());
    }
  }
  RemoveTemporaries();
  return error_;
}

std::string WriteFileAtomically(const std::string& path,
                                const std::function<void(std::ostream&)>& write) {
  AtomicFileSet file;
  file.Add(path, write);
  return file.Commit();
}

}  // namespace io
}  // namespace hex_slam
