#include "hex_slam/matching/scan_matcher.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace hex_slam {
namespace {

// Relative eigenvalue below which a Hessian direction counts as unconstrained.
constexpr double kSingularRatio = 1e-9;

}  // namespace

std::vector<std::string> ScanMatcherOptions::Validate() const {
  std::vector<std::string> errors;
  auto require = [&errors](bool ok, const std::string& message) {
    if (!ok) errors.push_back(message);
  };
  require(max_iterations_coarse >= 0, "scan_match_max_iterations_coarse must be >= 0");
  require(max_iterations_fine >= 1, "scan_match_max_iterations_fine must be >= 1");
  require(translation_tolerance_cells > 0.0, "scan_match_translation_tolerance_cells must be > 0");
  require(angle_tolerance > 0.0, "scan_match_angle_tolerance must be > 0");
  require(max_angle_step > 0.0, "scan_match_max_angle_step must be > 0");
  require(max_translation_step_cells > 0.0, "scan_match_max_translation_step_cells must be > 0");
  require(coarse_point_spacing_cells >= 0.0, "scan_match_coarse_point_spacing_cells must be >= 0");
  require(coarsest_min_move_cells >= 0.0, "scan_match_coarsest_min_move_cells must be >= 0");
  require(robust_loss_scale == 0.0 ||
              (robust_loss_scale >= kMinRobustLossScale && std::isfinite(robust_loss_scale)),
          "scan_match_robust_loss_scale must be 0 (off) or finite and >= 1e-6");
  require(odometry_translation_weight >= 0.0 && std::isfinite(odometry_translation_weight),
          "scan_match_odometry_translation_weight must be finite and >= 0");
  return errors;
}

void UseHectorsMethod(ScanMatcherOptions* options) {
  options->subcell_offsets = false;
  options->verify_converged_step = true;
  options->angle_tolerance_from_range = false;
  options->coarsest_min_move_cells = 0.0;
  options->robust_loss_scale = 0.0;
  options->odometry_translation_weight = 0.0;
}

double EndpointMoveBound(const Pose2& from, const Pose2& to, double reach) {
  return (to.translation() - from.translation()).norm() +
         std::abs(NormalizeAngle(to.theta - from.theta)) * reach;
}

double MeanRange(const std::vector<Eigen::Vector2d>& points) {
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) sum += p.norm();
  return points.empty() ? 0.0 : sum / points.size();
}

double Reach(const std::vector<Eigen::Vector2d>& points) {
  double reach_sq = 0.0;
  for (const Eigen::Vector2d& p : points) reach_sq = std::max(reach_sq, p.squaredNorm());
  return std::sqrt(reach_sq);
}

Eigen::Matrix3d CovarianceFromHessian(const Eigen::Matrix3d& hessian, double cost, int points) {
  const double dof = std::max(1, points - 3);
  const double sigma2 = std::max(cost / dof, 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(hessian);
  const Eigen::Vector3d values = eig.eigenvalues();
  const double largest = std::max(values.maxCoeff(), 0.0);
  Eigen::Vector3d inverse;
  for (int i = 0; i < 3; ++i) {
    inverse[i] = values[i] > kSingularRatio * largest && values[i] > 0.0
                     ? std::min(sigma2 / values[i], kUnconstrainedVariance)
                     : kUnconstrainedVariance;
  }
  return eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
}

void DecimateScan(const std::vector<Eigen::Vector2d>& points, double min_spacing,
                  std::vector<Eigen::Vector2d>* kept) {
  kept->clear();
  ForEachKeptEndpoint(points, min_spacing, [kept](const Eigen::Vector2d& p) { kept->push_back(p); });
}

}  // namespace hex_slam
