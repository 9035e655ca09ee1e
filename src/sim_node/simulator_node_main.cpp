// hex_slam_sim: see simulator_node.h.
#include <cstdio>
#include <stdexcept>

#include <ros/ros.h>

#include "simulator_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "hex_slam_sim");
  try {
    hex_slam::SimulatorNode node{ros::NodeHandle(), ros::NodeHandle("~")};
    node.Run();
  } catch (const std::exception& e) {
    // To stderr as well: rosconsole may not be up when the parameters are read.
    std::fprintf(stderr, "hex_slam_sim: error: %s\n", e.what());
    ROS_FATAL("hex_slam_sim: %s", e.what());
    return 1;
  }
  return 0;
}
