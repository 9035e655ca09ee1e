// Shared by slam.cpp and slam_tracking.cpp (the Slam class's two halves).
#ifndef HEX_SLAM_CORE_SLAM_INTERNAL_H_
#define HEX_SLAM_CORE_SLAM_INTERNAL_H_

#include <string>

namespace hex_slam {
namespace internal {

// The wide recovery window (every heading, with a long-range lidar) and the search while lost
// (hector's two levels leave a coarsest cell of 0.1 m: ±1 m and pi/64 took 25-32 thousand
// poses) can take more than their budget; rather than refuse them, their steps may be twice as
// coarse (a coarsest cell instead of half of one, and as much at the range that sets the
// angular step): the nearest searched pose still lies inside Gauss–Newton's basin.
constexpr double kMaxSearchStepCoarsening = 2.0;

// Joins the messages of one scan's events (an odometry fault, a refused search, too few beams).
inline void AppendMessage(const std::string& more, std::string* message) {
  *message += (message->empty() ? "" : "; ") + more;
}

}  // namespace internal
}  // namespace hex_slam

#endif  // HEX_SLAM_CORE_SLAM_INTERNAL_H_
