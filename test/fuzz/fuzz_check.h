// What a fuzz target asserts beyond "no crash, no sanitizer report": a promise a parser makes to
// the code downstream of it. A broken promise aborts, so libFuzzer keeps the input.
#ifndef HEX_SLAM_TEST_FUZZ_FUZZ_CHECK_H_
#define HEX_SLAM_TEST_FUZZ_FUZZ_CHECK_H_

#include <cstdio>
#include <cstdlib>

#define HEX_SLAM_FUZZ_CHECK(condition)                                            \
  do {                                                                            \
    if (!(condition)) {                                                           \
      std::fprintf(stderr, "fuzz check failed: %s (%s:%d)\n", #condition, __FILE__, \
                   __LINE__);                                                     \
      std::abort();                                                               \
    }                                                                             \
  } while (false)

#endif  // HEX_SLAM_TEST_FUZZ_FUZZ_CHECK_H_
