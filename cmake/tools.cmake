# Command-line tools over the core; each ends its output with a RESULT line.
add_executable(hex_slam_core_bench src/tools/core_benchmark_main.cpp)
target_link_libraries(hex_slam_core_bench hex_slam_core hex_slam_sim)

add_executable(hex_slam_demo src/tools/demo_main.cpp)
target_link_libraries(hex_slam_demo hex_slam_core hex_slam_sim hex_slam_io)
# The demo's maze is worlds/maze.yaml in the source tree.
target_compile_definitions(hex_slam_demo PRIVATE HEX_SLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

add_executable(hex_slam_plan src/tools/plan_main.cpp)
target_link_libraries(hex_slam_plan hex_slam_core hex_slam_io hex_slam_logs)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_tools_test test/tools/tools_smoke_test.cpp test/test_main.cpp)
  if(TARGET hex_slam_tools_test)
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
