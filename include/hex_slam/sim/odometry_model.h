// Wheel odometry that drifts like a real robot's: every step's motion is scaled by a systematic
// error and perturbed by Gaussian noise whose variance grows with the distance driven and the
// angle turned (a random walk), so the drift after a path does not depend on the sampling rate.
#ifndef HEX_SLAM_SIM_ODOMETRY_MODEL_H_
#define HEX_SLAM_SIM_ODOMETRY_MODEL_H_

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace sim {

struct OdometryNoise {
  // Random walk: the standard deviation of the error after 1 m driven (or 1 rad turned); after a
  // distance L it is stddev·sqrt(L).
  double translation_stddev = 0.0;           // m per sqrt(m) driven
  double rotation_stddev = 0.0;              // rad per sqrt(rad) turned
  double rotation_stddev_per_distance = 0.0;  // rad per sqrt(m) driven
  // Systematic: reported distance = (1 + e)·true distance (a wrong wheel radius), reported turn
  // = (1 + e)·true turn (a wrong wheel base).
  double translation_scale_error = 0.0;
  double rotation_scale_error = 0.0;

  // A typical differential-drive robot on a hard floor: 1 cm and 0.5° of random walk per metre,
  // 1% scale errors.
  static OdometryNoise Typical();

  // Empty when valid; otherwise one message per bad field, naming it.
  std::vector<std::string> Validate() const;
};

class DriftingOdometry {
 public:
  // Starts reporting `start` for the first true pose it is given. Throws std::invalid_argument
  // when `noise` is invalid.
  DriftingOdometry(const OdometryNoise& noise, std::uint64_t seed, const Pose2& start = Pose2());

  // Feeds the next true pose (the robot's motion since the previous one is what gets noised) and
  // returns the odometry pose.
  const Pose2& Update(const Pose2& true_pose);
  const Pose2& pose() const { return pose_; }

 private:
  OdometryNoise noise_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_;
  bool started_ = false;
  Pose2 last_true_;
  Pose2 pose_;
};

}  // namespace sim
}  // namespace hex_slam

#endif  // HEX_SLAM_SIM_ODOMETRY_MODEL_H_
