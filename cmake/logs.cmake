# Real robots' logs: CARMEN and bag readers, hex_slam_offline, hex_slam_eval, carmen_to_bag.
# hex_slam_logs is ROS-free (core + io); hex_slam_bag is the one part that links rosbag and tf2.
add_library(hex_slam_logs
  src/logs/carmen_reader.cpp
  src/logs/evaluation/map_consistency.cpp
  src/logs/evaluation/relations.cpp
  src/logs/evaluation/sample_statistics.cpp
  src/logs/evaluation/trajectory_error.cpp
  src/logs/evaluation/trajectory_lookup.cpp
  src/logs/offline/offline_config.cpp
  src/logs/offline/offline_runner.cpp
  src/logs/offline/progress_bar.cpp
  src/logs/offline/resource_usage.cpp
  src/logs/offline/run_outputs.cpp
  src/logs/offline/tool_arguments.cpp
  src/logs/stamp_order.cpp)
target_link_libraries(hex_slam_logs hex_slam_core hex_slam_io)

add_library(hex_slam_bag src/logs/bag_messages.cpp src/logs/bag_reader.cpp src/logs/bag_writer.cpp)
target_include_directories(hex_slam_bag PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(hex_slam_bag hex_slam_logs hex_slam_ros ${catkin_LIBRARIES})

add_executable(hex_slam_offline src/tools/offline_main.cpp)
target_link_libraries(hex_slam_offline hex_slam_logs hex_slam_bag hex_slam_command_line)

add_executable(hex_slam_eval src/tools/eval_main.cpp)
target_link_libraries(hex_slam_eval hex_slam_logs hex_slam_command_line)

add_executable(carmen_to_bag src/tools/carmen_to_bag_main.cpp)
target_link_libraries(carmen_to_bag hex_slam_logs hex_slam_bag hex_slam_command_line)

add_executable(sim_to_bag src/tools/sim_to_bag_main.cpp)
target_link_libraries(sim_to_bag hex_slam_logs hex_slam_bag hex_slam_sim hex_slam_command_line)
target_compile_definitions(sim_to_bag PRIVATE HEX_SLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

if(CATKIN_ENABLE_TESTING)
  get_filename_component(HEX_SLAM_REAL_SOURCE_DIR "${PROJECT_SOURCE_DIR}" REALPATH)
  set(HEX_SLAM_DEFAULT_DATA_DIR "${HEX_SLAM_REAL_SOURCE_DIR}/../shared/data")

  catkin_add_gtest(hex_slam_logs_test
    test/logs/carmen_reader_test.cpp
    test/logs/evaluation/map_consistency_test.cpp
    test/logs/evaluation/relations_test.cpp
    test/logs/evaluation/sample_statistics_test.cpp
    test/logs/evaluation/trajectory_error_test.cpp
    test/logs/evaluation/trajectory_lookup_test.cpp
    test/logs/intel_regression_test.cpp
    test/logs/localization_test.cpp
    test/logs/offline/offline_config_test.cpp
    test/logs/offline/offline_runner_test.cpp
    test/logs/offline/progress_bar_test.cpp
    test/logs/offline/run_outputs_test.cpp
    test/logs/offline/tool_arguments_test.cpp
    test/logs/stamp_order_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_logs_test)
    target_link_libraries(hex_slam_logs_test hex_slam_logs hex_slam_sim)
    target_include_directories(hex_slam_logs_test PRIVATE test/logs)
    target_compile_definitions(hex_slam_logs_test PRIVATE
      HEX_SLAM_DEFAULT_DATA_DIR="${HEX_SLAM_DEFAULT_DATA_DIR}"
      HEX_SLAM_SOURCE_DIR="${HEX_SLAM_REAL_SOURCE_DIR}")
  endif()

  # The parts that read and write bags.
  catkin_add_gtest(hex_slam_bag_test
    test/logs/bag_messages_test.cpp
    test/logs/bag_reader_test.cpp
    test/logs/bag_writer_test.cpp
    test/logs/ccny_bag_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_bag_test)
    target_include_directories(hex_slam_bag_test PRIVATE ${catkin_INCLUDE_DIRS})
    target_link_libraries(hex_slam_bag_test hex_slam_bag hex_slam_sim ${catkin_LIBRARIES})
    target_compile_definitions(hex_slam_bag_test PRIVATE
      HEX_SLAM_DEFAULT_DATA_DIR="${HEX_SLAM_DEFAULT_DATA_DIR}")
  endif()

  catkin_add_gtest(hex_slam_logs_tools_test test/logs/logs_tools_test.cpp test/test_main.cpp)
  if(TARGET hex_slam_logs_tools_test)
    target_link_libraries(hex_slam_logs_tools_test hex_slam_io hex_slam_sim)
    target_compile_definitions(hex_slam_logs_tools_test PRIVATE
      HEX_SLAM_TOOLS_DIR="${CATKIN_DEVEL_PREFIX}/lib/hex_slam")
    add_dependencies(hex_slam_logs_tools_test hex_slam_offline hex_slam_eval carmen_to_bag
                     hex_slam_plan hex_slam_loop_bench)
  endif()
endif()

# Loop closure against the truth on the simulated building loop.
add_executable(hex_slam_loop_bench src/tools/loop_benchmark_main.cpp)
target_link_libraries(hex_slam_loop_bench hex_slam_logs hex_slam_sim hex_slam_command_line)
install(TARGETS hex_slam_loop_bench RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
