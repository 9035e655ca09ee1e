// The parameters of hex_slam_offline: every SLAM parameter (SlamParameterTable), plus the few ROS
// interface parameters of hector_mapping / hex_slam_node that mean something offline (the scan
// topic and frames of a bag, whether to use odometry). So the node's YAML file configures an
// offline run as it is; the node's other ROS-interface keys (publishing, tf, services) are
// accepted and reported as ignored. Any other key is an error, as everywhere.
#ifndef HEX_SLAM_LOGS_OFFLINE_OFFLINE_CONFIG_H_
#define HEX_SLAM_LOGS_OFFLINE_OFFLINE_CONFIG_H_

#include <map>
#include <string>
#include <vector>

#include "hex_slam/common/parameter_table.h"
#include "hex_slam/mapping/slam_options.h"

namespace hex_slam {
namespace logs {

// Where an offline run's SlamOptions defaults differ from the node's (NodeConfig): the global map
// is drawn once at the end (kept live it would cost a map insertion per inserted scan for
// nothing), and the loop-closure worker runs at the scan path's priority (the run waits for it
// at its end anyway; at +10 on a loaded machine it would get a tenth of a core). A parameter file
// or --set may still change either.
void UseOfflineDefaults(SlamOptions* options);

struct OfflineConfig {
  OfflineConfig() { UseOfflineDefaults(&slam); }
  SlamOptions slam;
  std::string scan_topic = "/scan";
  std::string base_frame = "base_link";
  std::string odom_frame = "odom";
  bool use_odometry = true;
};

// hector_mapping's (and the node's) parameters about ROS plumbing only: publishing, tf
// broadcasting, services, queues, the map frame's name.
std::vector<std::string> RosInterfaceOnlyKeys();

ParameterTable OfflineParameterTable(OfflineConfig* config);

// Applies `values` (a parameter file's, then command-line overrides) to `config`. Keys in
// RosInterfaceOnlyKeys() are appended to `ignored`; every other problem becomes one message in
// the result.
std::vector<std::string> ApplyOfflineParameters(const std::map<std::string, std::string>& values,
                                                OfflineConfig* config,
                                                std::vector<std::string>* ignored);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_OFFLINE_OFFLINE_CONFIG_H_
