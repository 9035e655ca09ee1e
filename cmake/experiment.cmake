# The paper's experiment: the simulator node, worlds, and hex_slam_bench.

# Offline and ROS-free: the hex-vs-square table of the paper's scenarios.
add_executable(hex_slam_bench src/tools/bench_main.cpp)
target_link_libraries(hex_slam_bench hex_slam_core hex_slam_sim hex_slam_io
                      hex_slam_command_line)
# The worlds, the plot script and (beside the checkout) the data folder are found from here.
target_compile_definitions(hex_slam_bench PRIVATE HEX_SLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# hex_slam_sim, the simulator node (stage_ros's interface), over the simulation library.
add_executable(hex_slam_sim_node src/sim_node/simulator_node.cpp src/sim_node/simulator_node_main.cpp)
set_target_properties(hex_slam_sim_node PROPERTIES OUTPUT_NAME hex_slam_sim)
target_include_directories(hex_slam_sim_node PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(hex_slam_sim_node hex_slam_ros hex_slam_sim hex_slam_io hex_slam_core
  ${catkin_LIBRARIES})
add_dependencies(hex_slam_sim_node ${catkin_EXPORTED_TARGETS})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_sim_test
    test/sim/image_world_test.cpp
    test/sim/lidar_model_test.cpp
    test/sim/odometry_model_test.cpp
    test/sim/path_file_test.cpp
    test/sim/placed_world_test.cpp
    test/sim/scenario_test.cpp
    test/sim/scenario_run_test.cpp
    test/sim/simulated_robot_test.cpp
    test/sim/simulator_options_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_sim_test)
    target_link_libraries(hex_slam_sim_test hex_slam_sim hex_slam_io hex_slam_core)
    target_compile_definitions(hex_slam_sim_test PRIVATE
      HEX_SLAM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  endif()
endif()

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  add_rostest(test/sim_ros/sim_node.test DEPENDENCIES hex_slam_sim_node)
  add_rostest(test/sim_ros/evaluator.test DEPENDENCIES hex_slam_sim_node)
  find_package(roslaunch REQUIRED)
  roslaunch_add_file_check(launch/sim_maze.launch)
  roslaunch_add_file_check(launch/sim_slam_run.launch)
  # The paper's maze through ROS: hex and square side by side on the same simulated scans.
  add_rostest(test/sim_ros/sim_maze.test DEPENDENCIES hex_slam_sim_node hex_slam_node)
  # The robot launch files, unchanged, on simulated robots.
  roslaunch_add_file_check(launch/sim_rosbot.launch)
  add_rostest(test/sim_ros/rosbot_sim.test DEPENDENCIES hex_slam_sim_node hex_slam_node)
  add_rostest(test/sim_ros/stata/stata_sim.test DEPENDENCIES hex_slam_sim_node hex_slam_node)
  add_rostest(test/sim_ros/localization/localization_sim.test DEPENDENCIES hex_slam_sim_node hex_slam_node)
  add_rostest(test/sim_ros/localization/localization_far_sim.test DEPENDENCIES hex_slam_sim_node hex_slam_node)
endif()

# The tools' smoke test (tools.cmake) runs hex_slam_bench --quick too.
if(TARGET hex_slam_tools_test)
  add_dependencies(hex_slam_tools_test hex_slam_bench)
endif()
