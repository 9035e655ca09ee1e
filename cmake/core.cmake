# The ROS-free core: Eigen only, never a ROS header; Ceres (kept out of the headers) solves the
# pose graph.
find_package(Ceres REQUIRED)
add_library(hex_slam_core
  src/core/mapping/constraint_builder.cpp
  src/core/mapping/global_localizer.cpp
  src/core/mapping/loop_closure.cpp
  src/core/mapping/loop_closure_options.cpp
  src/core/mapping/loop_closure_worker.cpp
  src/core/mapping/pose_graph.cpp
  src/core/mapping/pose_graph_solution.cpp
  src/core/matching/fast_correlative_scan_matcher.cpp
  src/core/matching/precomputation_grid.cpp
  src/core/correlative_search.cpp
  src/core/cube.cpp
  src/core/grid_map.cpp
  src/core/hex_lattice.cpp
  src/core/hex_planner.cpp
  src/core/hex_scan_matcher.cpp
  src/core/input_limits.cpp
  src/core/match_covariance.cpp
  src/core/occupancy_model.cpp
  src/core/parameter_table.cpp
  src/core/pose2.cpp
  src/core/ray_traversal.cpp
  src/core/scan_matcher.cpp
  src/core/scan_sanitizer.cpp
  src/core/sensor_mount.cpp
  src/core/slam.cpp
  src/core/slam_options.cpp
  src/core/slam_tracking.cpp
  src/core/square_lattice.cpp
  src/core/square_scan_matcher.cpp
  src/core/tracking_state.cpp)
target_include_directories(hex_slam_core PUBLIC include ${EIGEN3_INCLUDE_DIR})
target_link_libraries(hex_slam_core PRIVATE Ceres::ceres)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_core_test
    test/core/correlative_search_test.cpp
    test/core/cube_test.cpp
    test/core/extreme_coordinates_test.cpp
    test/core/global_localization_test.cpp
    test/core/hex_lattice_test.cpp
    test/core/hex_planner_test.cpp
    test/core/hex_interpolation_test.cpp
    test/core/ray_traversal_test.cpp
    test/core/gauss_newton_test.cpp
    test/core/grid_index_test.cpp
    test/core/grid_map_test.cpp
    test/core/hex_scan_matcher_test.cpp
    test/core/square_scan_matcher_test.cpp
    test/core/scan_matcher_test.cpp
    test/core/scan_sanitizer_test.cpp
    test/core/sensor_mount_test.cpp
    test/core/parameter_table_test.cpp
    test/core/slam_test.cpp
    test/core/slam_tracking_test.cpp
    test/core/tracking_state_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_core_test)
    target_link_libraries(hex_slam_core_test hex_slam_core hex_slam_sim)
  endif()
endif()

# Loop closure: the branch-and-bound matcher, submaps, the pose graph and its worker.
if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_mapping_test
    test/core/mapping/active_submaps_test.cpp
    test/core/mapping/constraint_builder_test.cpp
    test/core/mapping/loop_closure_test.cpp
    test/core/mapping/pose_graph_test.cpp
    test/core/matching/fast_correlative_scan_matcher_test.cpp
    test/core/matching/precomputation_grid_test.cpp
    test/core/slam_loop_closure_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_mapping_test)
    target_link_libraries(hex_slam_mapping_test hex_slam_core hex_slam_sim)
  endif()
endif()
