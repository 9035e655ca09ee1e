# The ROS node (hex_slam_node), its ROS adapters, and its rostests.

# What every hex_slam ROS program shares (hex_slam_node, hex_slam_sim, the bag reader and writer):
# the rosparam loader, the planar pose <-> message conversions and the scan message conversion.
add_library(hex_slam_ros src/ros/rosparam_reader.cpp src/ros/pose_msgs.cpp src/ros/scan_msgs.cpp)
target_include_directories(hex_slam_ros PUBLIC src/ros ${catkin_INCLUDE_DIRS})
target_link_libraries(hex_slam_ros hex_slam_core ${catkin_LIBRARIES})

add_library(hex_slam_node_lib
  src/node/map_output/hex_map_marker.cpp
  src/node/map_output/map_saver.cpp
  src/node/map_output/map_snapshot.cpp
  src/node/map_output/redrawn_map.cpp
  src/node/node_diagnostics.cpp
  src/node/node_options.cpp
  src/node/ros_input/msg_conversion.cpp
  src/node/ros_input/tf_helper.cpp
  src/node/slam_node.cpp
  src/node/slam_node_map_output.cpp
  src/node/slam_node_path_planning.cpp
  src/node/trajectory_recorder.cpp)
target_include_directories(hex_slam_node_lib PUBLIC src/node ${catkin_INCLUDE_DIRS}
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_link_libraries(hex_slam_node_lib hex_slam_ros hex_slam_core hex_slam_io hex_slam_logs
  ${catkin_LIBRARIES})
add_dependencies(hex_slam_node_lib ${PROJECT_NAME}_generate_messages_cpp)

add_executable(hex_slam_node src/node/hex_slam_node_main.cpp)
target_link_libraries(hex_slam_node hex_slam_node_lib)

install(TARGETS hex_slam_node RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY launch config rviz DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_node_test
    test/node/map_output/hex_map_marker_test.cpp
    test/node/map_output/map_saver_test.cpp
    test/node/map_output/map_snapshot_test.cpp
    test/node/map_output/redrawn_map_test.cpp
    test/node/node_diagnostics_test.cpp
    test/node/node_options_test.cpp
    test/node/pose_msgs_test.cpp
    test/node/scan_msgs_test.cpp
    test/node/ros_input/msg_conversion_test.cpp
    test/node/ros_input/scan_clock_test.cpp
    test/node/ros_input/scan_queue_test.cpp
    test/node/ros_input/tf_helper_test.cpp
    test/node/timing_stats_test.cpp
    test/node/trajectory_recorder_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_node_test)
    target_link_libraries(hex_slam_node_test hex_slam_node_lib hex_slam_sim)
    target_include_directories(hex_slam_node_test PRIVATE test/io test/node)
    target_compile_definitions(hex_slam_node_test PRIVATE
      HEX_SLAM_CONFIG_DIR="${CMAKE_CURRENT_SOURCE_DIR}/config")
  endif()
endif()

if(CATKIN_ENABLE_TESTING)
  # Each launches the node with a simulated robot (test/ros/room_scan_publisher.py) and a checker.
  find_package(rostest REQUIRED)
  # Every shipped launch file parses, its arguments resolve and its nodes exist.
  find_package(roslaunch REQUIRED)
  roslaunch_add_file_check(launch/hex_slam.launch)
  roslaunch_add_file_check(launch/rosbot_rplidar.launch)
  roslaunch_add_file_check(launch/mit_stata_bag.launch bag:=stata.bag)
  add_rostest(test/ros/room/room_mapping.test)
  add_rostest(test/ros/bad_input/bad_input.test)
  add_rostest(test/ros/hector/moving_mount.test)
  add_rostest(test/ros/hector/mapping_default.test)
  add_rostest(test/ros/bad_input/parameters.test)
  add_rostest(test/ros/room/room_mapping_square.test)
  add_rostest(test/ros/room/room_mapping_single_map.test)
  add_rostest(test/ros/room/room_no_odometry.test)
  add_rostest(test/ros/room/tracking_state.test)
  add_rostest(test/ros/bags/ccny_bag.test DEPENDENCIES hex_slam_offline)
  add_rostest(test/ros/bags/intel_replay.test DEPENDENCIES carmen_to_bag hex_slam_offline hex_slam_eval)
endif()
