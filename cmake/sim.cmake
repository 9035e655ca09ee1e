# Simulation without ROS: worlds, the lidar model and motion, used by tests, the demo, the
# benchmark and the simulator node.
add_library(hex_slam_sim
  src/sim/building_loop.cpp
  src/sim/image_world.cpp
  src/sim/lidar_model.cpp
  src/sim/odometry_model.cpp
  src/sim/path_file.cpp
  src/sim/room_drive.cpp
  src/sim/scenario.cpp
  src/sim/scenario_run.cpp
  src/sim/segment_world.cpp
  src/sim/simulated_robot.cpp
  src/sim/simulator_options.cpp
  src/sim/waypoint_path.cpp)
# Image worlds and path files are read through the IO library.
target_link_libraries(hex_slam_sim hex_slam_core hex_slam_io)
