// Writing files so that a reader never sees half of one: write a temporary file beside the
// target, flush it to disk, then rename it over the target (atomic on POSIX file systems). Files
// that belong together (a map's .pgm and .yaml, save_map's three) are written as one set: every
// temporary first, the renames only once all of them were written.
#ifndef HEX_SLAM_IO_ATOMIC_FILE_H_
#define HEX_SLAM_IO_ATOMIC_FILE_H_

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace hex_slam {
namespace io {

class AtomicFileSet {
 public:
  AtomicFileSet() = default;
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;
  // Removes the temporaries of a set that was not committed.
  ~AtomicFileSet();

  // Calls `write` with a stream to a temporary beside `path`. A `write` that throws or leaves the
  // stream failed, or a temporary that cannot be made, is the set's error: later Adds do nothing
  // and Commit() fails.
  void Add(const std::string& path, const std::function<void(std::ostream&)>& write);
  // Records an error found outside Add (bad data to write): Commit() then fails with it.
  void Fail(const std::string& error);

  // Renames every temporary onto its target. Returns an empty string, or the error, and then no
  // target has changed: a target that is a directory is found before anything is renamed, and
  // should a rename still fail, the targets already replaced get their previous contents back
  // (or are removed, if they are new). Temporaries never stay behind.
  std::string Commit();

 private:
  struct Pending {
    std::string path;
    std::string temp;
  };
  void RemoveTemporaries();

  std::vector<Pending> pending_;
  std::string error_;
  bool committed_ = false;
};

// One file on its own: an AtomicFileSet of one. Returns an empty string on success; otherwise an
// error message, and neither `path` nor a temporary is left changed or behind.
std::string WriteFileAtomically(const std::string& path,
                                const std::function<void(std::ostream&)>& write);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_ATOMIC_FILE_H_
