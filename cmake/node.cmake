# The ROS node (hex_slam_node), its ROS adapters, and its rostests.
