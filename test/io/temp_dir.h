// A fresh temporary directory per test, removed afterwards.
#ifndef HEX_SLAM_TEST_IO_TEMP_DIR_H_
#define HEX_SLAM_TEST_IO_TEMP_DIR_H_

#include <dirent.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace hex_slam {
namespace testing_util {

class TempDir {
 public:
  TempDir() {
    char pattern[] = "/tmp/hex_slam_test_XXXXXX";
    path_ = ::mkdtemp(pattern);
  }
  ~TempDir() {
    for (const std::string& name : Files()) ::unlink((path_ + "/" + name).c_str());
    ::rmdir(path_.c_str());
  }
  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }
  std::vector<std::string> Files() const {
    std::vector<std::string> names;
    if (DIR* dir = ::opendir(path_.c_str())) {
      while (dirent* entry = ::readdir(dir)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..") names.push_back(name);
      }
      ::closedir(dir);
    }
    return names;
  }

 private:
  std::string path_;
};

}  // namespace testing_util
}  // namespace hex_slam

#endif  // HEX_SLAM_TEST_IO_TEMP_DIR_H_
