# Command-line tools over the core; each ends its output with a RESULT line.
add_executable(hex_slam_core_bench src/tools/core_benchmark_main.cpp)
target_link_libraries(hex_slam_core_bench hex_slam_core hex_slam_sim)

add_executable(hex_slam_demo src/tools/demo_main.cpp)
target_link_libraries(hex_slam_demo hex_slam_core hex_slam_sim hex_slam_io)
