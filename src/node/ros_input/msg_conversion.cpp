#include "ros_input/msg_conversion.h"

#include <algorithm>
#include <cmath>

namespace hex_slam {
namespace node {
namespace {

// Indices of x, y and yaw in a 6x6 geometry_msgs covariance.
constexpr int kCovarianceIndex[3] = {0, 1, 5};
constexpr int kCovarianceSide = 6;

}  // namespace

boost::array<double, 36> ToCovarianceMsg(const Eigen::Matrix3d& covariance) {
  boost::array<double, 36> msg;
  msg.fill(0.0);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      msg[kCovarianceIndex[i] * kCovarianceSide + kCovarianceIndex[j]] = covariance(i, j);
    }
  }
  return msg;
}

sensor_msgs::PointCloud ToPointCloudMsg(const sensor_msgs::LaserScan& msg, double min_dist,
                                        double max_dist) {
  sensor_msgs::PointCloud cloud;
  cloud.header = msg.header;
  const double lo = std::max<double>(min_dist, msg.range_min);
  const double hi = std::min<double>(max_dist, msg.range_max);
  for (std::size_t i = 0; i < msg.ranges.size(); ++i) {
    const double r = msg.ranges[i];
    if (!std::isfinite(r) || r < lo || r > hi) continue;
    const double angle = msg.angle_min + static_cast<double>(i) * msg.angle_increment;
    geometry_msgs::Point32 p;
    p.x = static_cast<float>(r * std::cos(angle));
    p.y = static_cast<float>(r * std::sin(angle));
    cloud.points.push_back(p);
  }
  return cloud;
}

std::string CleanFrameId(const std::string& frame_id) {
  const std::size_t first = frame_id.find_first_not_of('/');
  return first == std::string::npos ? std::string() : frame_id.substr(first);
}

nav_msgs::OccupancyGrid ToOccupancyGridMsg(const io::OccupancyRaster& raster,
                                           const std::string& frame, const ros::Time& stamp) {
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(raster.resolution);
  msg.info.width = static_cast<std::uint32_t>(raster.width);
  msg.info.height = static_cast<std::uint32_t>(raster.height);
  msg.info.origin.position.x = raster.origin.x();
  msg.info.origin.position.y = raster.origin.y();
  msg.info.origin.orientation.w = 1.0;
  msg.data = raster.data;
  return msg;
}

}  // namespace node
}  // namespace hex_slam
