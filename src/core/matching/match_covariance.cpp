#include "hex_slam/matching/match_covariance.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Eigenvalues>

#include "hex_slam/common/input_limits.h"

namespace hex_slam {
namespace {

// Walls are found by splitting the scan, in scan order, into straight runs (split-and-merge):
// a run whose points all lie within this distance (m) of the chord between its ends is one
// straight surface, about three times a lidar's range noise and under a cell. Its normal comes
// from the whole run: along a corridor, metres of wall, so its direction is known to a few
// milliradians. (A normal from each point's few neighbours was off by ~0.1 rad from 1 cm of range
// noise, and that noise alone put the along-corridor sigma at 2 cm after 4 m of sliding.)
constexpr double kLineTolerance = 0.03;
// Consecutive points farther apart than this (m) are not one surface, however straight.
constexpr double kMaxGap = 1.0;
// A straight run needs this many points for its direction to mean anything.
constexpr int kMinRunPoints = 4;

// The unit normal of the least-squares line through points [first, last].
Eigen::Vector2d FittedNormal(const std::vector<Eigen::Vector2d>& points, int first, int last) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i = first; i <= last; ++i) mean += points[i];
  mean /= last - first + 1;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (int i = first; i <= last; ++i) {
    const Eigen::Vector2d d = points[i] - mean;
    scatter += d * d.transpose();
  }
  // Eigenvalues ascending: the first eigenvector is across the line.
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(0);
}

// The point of (first, last) farthest from the chord between them, and that distance.
std::pair<int, double> FarthestFromChord(const std::vector<Eigen::Vector2d>& points, int first,
                                         int last) {
  const Eigen::Vector2d a = points[first];
  const Eigen::Vector2d chord = points[last] - a;
  const double length = chord.norm();
  std::pair<int, double> farthest{first, 0.0};
  for (int i = first + 1; i < last; ++i) {
    const Eigen::Vector2d d = points[i] - a;
    const double distance = length > 0.0 ? std::abs(chord.x() * d.y() - chord.y() * d.x()) / length
                                         : d.norm();
    if (distance > farthest.second) farthest = {i, distance};
  }
  return farthest;
}

}  // namespace

Eigen::Matrix3d UnknownPoseCovariance() {
  return kUnconstrainedVariance * Eigen::Matrix3d::Identity();
}

std::vector<Eigen::Vector2d> SurfaceNormals(const std::vector<Eigen::Vector2d>& points) {
  const int n = static_cast<int>(points.size());
  std::vector<Eigen::Vector2d> normals(points.size(), Eigen::Vector2d::Zero());
  // Runs of points without a gap, then each split at its farthest point until straight.
  std::vector<std::pair<int, int>> pending;
  for (int first = 0, i = 1; i <= n; ++i) {
    if (i == n || (points[i] - points[i - 1]).norm() > kMaxGap) {
      pending.emplace_back(first, i - 1);
      first = i;
    }
  }
  while (!pending.empty()) {
    const auto [first, last] = pending.back();
    pending.pop_back();
    if (last - first + 1 < kMinRunPoints) continue;
    const auto [split, distance] = FarthestFromChord(points, first, last);
    if (distance > kLineTolerance) {
      pending.emplace_back(first, split);
      pending.emplace_back(split + 1, last);
      continue;
    }
    const Eigen::Vector2d normal = FittedNormal(points, first, last);
    for (int i = first; i <= last; ++i) normals[i] = normal;
  }
  return normals;
}

Eigen::Matrix3d MatchCovariance(const MatchResult& match,
                                const std::vector<Eigen::Vector2d>& points) {
  if (match.num_points <= 0 || !match.hessian.allFinite() || !std::isfinite(match.cost) ||
      !IsFinite(match.pose)) {
    return UnknownPoseCovariance();
  }
  // The mean squared map gradient per endpoint: the translation block of ΣJᵀJ is Σ∇M∇Mᵀ.
  const double gradient_sq = (match.hessian(0, 0) + match.hessian(1, 1)) / match.num_points;
  const std::vector<Eigen::Vector2d> normals = SurfaceNormals(points);
  const double c = std::cos(match.pose.theta), s = std::sin(match.pose.theta);
  Eigen::Matrix2d rotation;
  rotation << c, -s, s, c;
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (normals[i].isZero()) continue;
    const Eigen::Vector2d q = rotation * points[i];   // endpoint from the robot, world axes
    const Eigen::Vector2d n = rotation * normals[i];  // its normal, world axes
    // How moving the pose by (x, y, theta) moves the endpoint along its normal.
    const Eigen::Vector3d g(n.x(), n.y(), q.x() * n.y() - q.y() * n.x());
    information += g * g.transpose();
  }
  return CovarianceFromHessian(gradient_sq * information, match.cost, match.num_points);
}

}  // namespace hex_slam
