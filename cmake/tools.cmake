# Command-line tools over the core; each ends its output with a RESULT line.
# Their command lines: CLI11 with the option kinds they share (src/tools/command_line.h).
find_package(CLI11 REQUIRED)
add_library(hex_slam_command_line STATIC src/tools/command_line.cpp)
target_link_libraries(hex_slam_command_line PUBLIC CLI11::CLI11 hex_slam_logs)

add_executable(hex_slam_core_bench src/tools/core_benchmark_main.cpp)
target_link_libraries(hex_slam_core_bench hex_slam_core hex_slam_sim hex_slam_command_line)

add_executable(hex_slam_demo src/tools/demo_main.cpp)
target_link_libraries(hex_slam_demo hex_slam_core hex_slam_sim hex_slam_io hex_slam_command_line)
# The demo's maze is worlds/maze.yaml in the source tree.
target_compile_definitions(hex_slam_demo PRIVATE HEX_SLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

add_executable(hex_slam_plan src/tools/plan_main.cpp)
target_link_libraries(hex_slam_plan hex_slam_core hex_slam_io hex_slam_logs hex_slam_command_line)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_tools_test
    test/tools/command_line_test.cpp test/tools/tools_smoke_test.cpp test/test_main.cpp)
  if(TARGET hex_slam_tools_test)
    target_link_libraries(hex_slam_tools_test hex_slam_command_line)
    target_include_directories(hex_slam_tools_test PRIVATE src/tools)
    target_compile_definitions(hex_slam_tools_test PRIVATE
      HEX_SLAM_TOOLS_DIR="${CATKIN_DEVEL_PREFIX}/lib/hex_slam")
    add_dependencies(hex_slam_tools_test hex_slam_demo hex_slam_core_bench)
  endif()
endif()

# Google Benchmark figures for the loop-closure matcher (built when libbenchmark-dev is there).
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(hex_slam_matching_bench src/tools/matching_benchmark_main.cpp)
  target_link_libraries(hex_slam_matching_bench hex_slam_core hex_slam_sim benchmark::benchmark)
  install(TARGETS hex_slam_matching_bench RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endif()
