// Every tool's main(): an exception nobody expected becomes one line on stderr and exit status 1,
// not std::terminate's abort and core dump in the middle of a script.
#ifndef HEX_SLAM_SRC_TOOLS_TOOL_MAIN_H_
#define HEX_SLAM_SRC_TOOLS_TOOL_MAIN_H_

#include <cstdio>
#include <exception>

namespace hex_slam {

inline int RunToolMain(int (*tool_main)(int, char**), int argc, char** argv) {
  try {
    return tool_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

}  // namespace hex_slam

#endif  // HEX_SLAM_SRC_TOOLS_TOOL_MAIN_H_
