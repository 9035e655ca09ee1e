# File formats and rendering: rasters, map_server maps, images. ROS-free.
find_package(PNG REQUIRED)
find_package(yaml-cpp REQUIRED)
add_library(hex_slam_io
  src/io/atomic_file.cpp
  src/io/bounded_line.cpp
  src/io/hex_map_file.cpp
  src/io/image_io.cpp
  src/io/map_image.cpp
  src/io/map_server_io.cpp
  src/io/number_rows.cpp
  src/io/occupancy_raster.cpp
  src/io/parameter_file.cpp
  src/io/trajectory_io.cpp)
target_link_libraries(hex_slam_io hex_slam_core ${PNG_LIBRARIES} yaml-cpp)
target_include_directories(hex_slam_io PRIVATE ${PNG_INCLUDE_DIRS})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(hex_slam_io_test
    test/io/atomic_file_test.cpp
    test/io/bounded_line_test.cpp
    test/io/hex_map_file_test.cpp
    test/io/image_io_test.cpp
    test/io/map_image_test.cpp
    test/io/map_server_io_test.cpp
    test/io/number_rows_test.cpp
    test/io/occupancy_raster_test.cpp
    test/io/parameter_file_test.cpp
    test/io/trajectory_io_test.cpp
    test/test_main.cpp)
  if(TARGET hex_slam_io_test)
    target_link_libraries(hex_slam_io_test hex_slam_io)
  endif()
endif()
