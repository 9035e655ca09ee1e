# The ROS-free core: Eigen only, never a ROS header; Ceres (kept out of the headers) solves the
# pose graph.
find_package(Ceres REQUIRED)
add_library(hex_slam_core
  src/core/common/input_limits.cpp
  src/core/common/heap_retention.cpp
  src/core/common/thread_clock.cpp
  src/core/common/thread_priority.cpp
  src/core/common/parameter_table.cpp
  src/core/geometry/cube.cpp
  src/core/geometry/hex_lattice.cpp
  src/core/geometry/pose2.cpp
  src/core/geometry/ray_traversal.cpp
  src/core/geometry/square_lattice.cpp
  src/core/map/grid_map.cpp
  src/core/map/occupancy_model.cpp
  src/core/mapping/loop_closure/constraint_builder.cpp
  src/core/mapping/loop_closure/drift_graph.cpp
  src/core/mapping/global_localizer.cpp
  src/core/mapping/loop_closure/loop_closure.cpp
  src/core/mapping/loop_closure/loop_closure_options.cpp
  src/core/mapping/loop_closure/loop_closure_worker.cpp
  src/core/mapping/loop_closure/pose_graph.cpp
  src/core/mapping/loop_closure/pose_graph_solution.cpp
  src/core/mapping/slam.cpp
  src/core/mapping/slam_options.cpp
  src/core/mapping/slam_tracking.cpp
  src/core/mapping/tracking_state.cpp
  src/core/matching/correlative_search.cpp
  src/core/matching/fast_correlative_scan_matcher.cpp
  src/core/matching/hex_scan_matcher.cpp
  src/core/matching/match_covariance.cpp
  src/core/matching/precomputation_grid.cpp
  src/core/matching/scan_matcher.cpp
  src/core/matching/square_scan_matcher.cpp
  src/core/matching/step_bounds.cpp
  src/core/planning/hex_planner.cpp
  src/core/sensor/grazing_endpoints.cpp
  src/core/sensor/scan_sanitizer.cpp
  src/core/sensor/sensor_mount.cpp)
target_include_directories(hex_slam_core PUBLIC include ${EIGEN3_INCLUDE_DIR})
# The core's private headers (ray walks, the Gauss-Newton loop) by folder: "geometry/ray_walk.h".
target_include_directories(hex_slam_core PRIVATE src/core)
target_link_libraries(hex_slam_core PRIVATE Ceres::ceres)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_core_test
    test/core/common/heap_retention_test.cpp
    test/core/common/parameter_table_test.cpp
    test/core/common/thread_priority_test.cpp
    test/core/geometry/cube_test.cpp
    test/core/geometry/grid_index_test.cpp
    test/core/geometry/hex_lattice_test.cpp
    test/core/geometry/ray_traversal_test.cpp
    test/core/map/extreme_coordinates_test.cpp
    test/core/map/grid_map_test.cpp
    test/core/map/hex_interpolation_test.cpp
    test/core/map/zeroed_array_test.cpp
    test/core/mapping/global_localization_test.cpp
    test/core/mapping/slam_test.cpp
    test/core/mapping/slam_tracking_test.cpp
    test/core/mapping/tracking_state_test.cpp
    test/core/matching/correlative_search_test.cpp
    test/core/matching/gauss_newton_test.cpp
    test/core/matching/hex_scan_matcher_test.cpp
    test/core/matching/scan_matcher_test.cpp
    test/core/matching/square_scan_matcher_test.cpp
    test/core/planning/hex_planner_test.cpp
    test/core/sensor/grazing_endpoints_test.cpp
    test/core/sensor/scan_sanitizer_test.cpp
    test/core/sensor/sensor_mount_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_core_test)
    target_link_libraries(hex_slam_core_test hex_slam_core hex_slam_sim)
  endif()
endif()

# Loop closure: the branch-and-bound matcher, submaps, the pose graph and its worker.
if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_mapping_test
    test/core/mapping/active_submaps_test.cpp
    test/core/mapping/loop_closure/constraint_builder_test.cpp
    test/core/mapping/loop_closure/drift_graph_test.cpp
    test/core/mapping/loop_closure/loop_closure_test.cpp
    test/core/mapping/loop_closure/pose_graph_test.cpp
    test/core/mapping/slam_loop_closure_test.cpp
    test/core/mapping/loop_closure/submap_cache_test.cpp
    test/core/matching/fast_correlative_scan_matcher_test.cpp
    test/core/matching/precomputation_grid_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_mapping_test)
    target_link_libraries(hex_slam_mapping_test hex_slam_core hex_slam_sim)
  endif()
endif()
