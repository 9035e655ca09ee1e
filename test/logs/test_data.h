// Where the tests find the real logs: $HEX_SLAM_DATA_DIR, else ../shared/data beside the
// package's source folder. Tests that need a file skip, saying which, when it is absent.
#ifndef HEX_SLAM_TEST_LOGS_TEST_DATA_H_
#define HEX_SLAM_TEST_LOGS_TEST_DATA_H_

#include <cstdlib>
#include <fstream>
#include <string>

namespace hex_slam {
namespace test {

inline std::string DataDir() {
  const char* env = std::getenv("HEX_SLAM_DATA_DIR");
  return env && *env ? std::string(env) : std::string(HEX_SLAM_DEFAULT_DATA_DIR);
}

inline std::string DataFile(const std::string& relative) { return DataDir() + "/" + relative; }

inline bool Readable(const std::string& path) { return std::ifstream(path).good(); }

inline const char* kIntelLog = "intel/intel_first5505.clf";
inline const char* kIntelRelations = "intel/intel.relations";
inline const char* kCcnyBag = "ccny_demo/laser_scan_matcher_demo.bag";

}  // namespace test
}  // namespace hex_slam

// Skips the test when `path` cannot be read.
#define HEX_SLAM_REQUIRE_DATA(path)                                                      \
  do {                                                                                   \
    if (!::hex_slam::test::Readable(path)) {                                             \
      GTEST_SKIP() << "real data absent: " << (path)                                     \
                   << " (set HEX_SLAM_DATA_DIR to the folder holding intel/ and ccny_demo/)"; \
    }                                                                                    \
  } while (0)

#endif  // HEX_SLAM_TEST_LOGS_TEST_DATA_H_
