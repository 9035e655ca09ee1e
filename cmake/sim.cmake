# Simulation without ROS: worlds, the lidar model and motion, used by tests, the demo, the
# benchmark and the simulator node.
add_library(hex_slam_sim
  src/sim/lidar_model.cpp
  src/sim/room_drive.cpp
  src/sim/segment_world.cpp
  src/sim/waypoint_path.cpp)
target_link_libraries(hex_slam_sim hex_slam_core)
