# What `catkin_make install` (or a binary package) ships: the libraries and headers other packages
# build on, every node and tool, the Python nodes the launch files start, and the data they read.
install(TARGETS hex_slam_core hex_slam_io hex_slam_sim hex_slam_logs hex_slam_bag hex_slam_ros
                hex_slam_node_lib
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_GLOBAL_BIN_DESTINATION})
install(TARGETS hex_slam_sim_node hex_slam_offline hex_slam_eval carmen_to_bag sim_to_bag hex_slam_bench
                hex_slam_core_bench hex_slam_demo hex_slam_plan
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY include/hex_slam/ DESTINATION ${CATKIN_PACKAGE_INCLUDE_DESTINATION})
install(DIRECTORY worlds DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
catkin_install_python(PROGRAMS
    scripts/run_if_installed.py scripts/sim_compare.py scripts/sim_evaluator.py
    scripts/tf_drop_frames.py scripts/plot_bench.py scripts/make_worlds.py
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
