// Shared by slam.cpp and slam_tracking.cpp (the Slam class's two halves).
#ifndef HEX_SLAM_CORE_SLAM_INTERNAL_H_
#define HEX_SLAM_CORE_SLAM_INTERNAL_H_

#include <string>

namespace hex_slam {
namespace internal {

// Joins the messages of one scan's events (an odometry fault, a refused search, too few beams).
inline void AppendMessage(const std::string& more, std::string* message) {
  *message += (message->empty() ? "" : "; ") + more;
}

}  // namespace internal
}  // namespace hex_slam

#endif  // HEX_SLAM_CORE_SLAM_INTERNAL_H_
