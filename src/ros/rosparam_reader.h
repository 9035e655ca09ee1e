// Every parameter under a node's private namespace as key -> text, the form a ParameterTable (and
// the YAML reader) takes, so rosparams go through the same table and checks as parameter files.
// The one rosparam loader of hex_slam_node and hex_slam_sim (library hex_slam_ros).
#ifndef HEX_SLAM_ROS_ROSPARAM_READER_H_
#define HEX_SLAM_ROS_ROSPARAM_READER_H_

#include <map>
#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace hex_slam {

struct PrivateParameters {
  // Keys relative to the namespace: "map_resolution", or "a/b" for a nested one.
  std::map<std::string, std::string> values;
  std::vector<std::string> non_scalar_keys;  // lists and other values no option can take
  std::string error;                         // the parameter server could not be read
};

PrivateParameters ReadPrivateParameters(const ros::NodeHandle& private_nh);

}  // namespace hex_slam

#endif  // HEX_SLAM_ROS_ROSPARAM_READER_H_
