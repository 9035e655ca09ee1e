#include "hex_slam/logs/evaluation/trajectory_error.h"

#include <algorithm>
#include <cmath>

namespace hex_slam {
namespace logs {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

}  // namespace

Pose2 AlignPoints(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to) {
  const std::size_t n = std::min(from.size(), to.size());
  if (n < 2) return Pose2();
  Eigen::Vector2d mean_from = Eigen::Vector2d::Zero(), mean_to = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_from += from[i];
    mean_to += to[i];
  }
  mean_from /= static_cast<double>(n);
  mean_to /= static_cast<double>(n);
  // The rotation maximising sum (to - mean_to) . R (from - mean_from) has
  // tan(theta) = sum cross / sum dot of the centred pairs.
  double dot = 0.0, cross = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = from[i] - mean_from, b = to[i] - mean_to;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
  }
  const double theta = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
  const Pose2 rotation(0.0, 0.0, theta);
  const Eigen::Vector2d t = mean_to - rotation * mean_from;
  return Pose2(t.x(), t.y(), theta);
}

TrajectoryErrorReport EvaluateTrajectory(const std::vector<io::StampedPose>& estimate,
                                         const std::vector<io::StampedPose>& ground_truth,
                                         const TrajectoryErrorOptions& options) {
  TrajectoryErrorReport report;
  report.poses = static_cast<int>(estimate.size());
  const TrajectoryLookup truth(ground_truth);
  std::vector<io::StampedPose> sorted = estimate;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const io::StampedPose& a, const io::StampedPose& b) { return a.stamp < b.stamp; });
  std::vector<double> stamps;
  std::vector<Pose2> est, ref;
  for (const io::StampedPose& p : sorted) {
    const std::optional<Pose2> g = truth.At(p.stamp, options.lookup);
    if (!g) continue;
    stamps.push_back(p.stamp);
    est.push_back(p.pose);
    ref.push_back(*g);
  }
  report.matched = static_cast<int>(est.size());
  std::vector<Eigen::Vector2d> from, to;
  for (std::size_t i = 0; i < est.size(); ++i) {
    from.push_back(est[i].translation());
    to.push_back(ref[i].translation());
  }
  report.alignment = AlignPoints(from, to);
  std::vector<double> ate_t, ate_r, rpe_t, rpe_r;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Pose2 aligned = report.alignment * est[i];
    ate_t.push_back((aligned.translation() - ref[i].translation()).norm());
    ate_r.push_back(std::abs(NormalizeAngle(aligned.theta - ref[i].theta)) * kDegreesPerRadian);
  }
  // RPE: each pose paired with the first one at least rpe_delta later.
  std::size_t j = 0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    j = std::max(j, i + 1);
    while (j < est.size() && stamps[j] < stamps[i] + options.rpe_delta) ++j;
    if (j >= est.size()) break;
    const Pose2 error = RelativePose(RelativePose(ref[i], ref[j]), RelativePose(est[i], est[j]));
    rpe_t.push_back(error.translation().norm());
    rpe_r.push_back(std::abs(error.theta) * kDegreesPerRadian);
  }
  report.ate_translation = Summarize(std::move(ate_t));
  report.ate_rotation = Summarize(std::move(ate_r));
  report.rpe_translation = Summarize(std::move(rpe_t));
  report.rpe_rotation = Summarize(std::move(rpe_r));
  return report;
}

}  // namespace logs
}  // namespace hex_slam
