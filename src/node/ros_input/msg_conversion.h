// Conversions between ROS messages and the core's types the node needs beyond pose_msgs.h:
// covariances, occupancy grids, point clouds (a scan: scan_msgs.h).
#ifndef HEX_SLAM_NODE_ROS_INPUT_MSG_CONVERSION_H_
#define HEX_SLAM_NODE_ROS_INPUT_MSG_CONVERSION_H_

#include <string>

#include <boost/array.hpp>
#include <Eigen/Core>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud.h>

#include "hex_slam/io/occupancy_raster.h"
#include "hex_slam/sensor/laser_scan.h"
#include "hex_slam/geometry/pose2.h"
#include "pose_msgs.h"  // the planar pose <-> message conversions (library hex_slam_ros)

namespace hex_slam {
namespace node {

// The planar (x, y, yaw) covariance in the 6x6 row-major layout of geometry_msgs (x y z roll
// pitch yaw); z, roll and pitch are exactly known (zero) in 2D.
boost::array<double, 36> ToCovarianceMsg(const Eigen::Matrix3d& covariance);

// hector_mapping's slam_cloud: the scan's returns as points in its own frame and stamp, those
// within the scan's range limits and [min_dist, max_dist] (laser_min_dist, laser_max_dist).
sensor_msgs::PointCloud ToPointCloudMsg(const sensor_msgs::LaserScan& msg, double min_dist,
                                        double max_dist);

// tf2 frame ids have no leading slash; tf1-era data (and some drivers) still send "/laser".
std::string CleanFrameId(const std::string& frame_id);

nav_msgs::OccupancyGrid ToOccupancyGridMsg(const io::OccupancyRaster& raster,
                                           const std::string& frame, const ros::Time& stamp);

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_ROS_INPUT_MSG_CONVERSION_H_
