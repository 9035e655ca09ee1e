// Every parameter under a node's private namespace as key -> text, the form ApplyNodeConfig (and
// the YAML reader) use, so rosparams go through the same table and checks as parameter files.
#ifndef HEX_SLAM_NODE_ROSPARAM_READER_H_
#define HEX_SLAM_NODE_ROSPARAM_READER_H_

#include <map>
#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace hex_slam {
namespace node {

struct PrivateParameters {
  // Keys relative to the namespace: "map_resolution", or "a/b" for a nested one.
  std::map<std::string, std::string> values;
  std::vector<std::string> non_scalar_keys;  // lists and other values no option can take
  std::string error;                         // the parameter server could not be read
};

PrivateParameters ReadPrivateParameters(const ros::NodeHandle& private_nh);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_ROSPARAM_READER_H_
