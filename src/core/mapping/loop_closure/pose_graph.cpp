#include "hex_slam/mapping/loop_closure/pose_graph.h"

#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <ceres/ceres.h>

namespace hex_slam {
namespace mapping {
namespace {

// The residual of one constraint on (x, y, θ) blocks. The angle error is wrapped to (-π, π] in
// the residual itself (atan2 of its sine and cosine, smooth for the Jacobian), which is what
// Ceres 2.1's deprecated LocalParameterization was used for; the solved angles are normalised
// afterwards.
class RelativePoseCost {
 public:
  RelativePoseCost(const Pose2& measured, double translation_weight, double rotation_weight)
      : measured_(measured),
        translation_weight_(translation_weight),
        rotation_weight_(rotation_weight) {}

  template <typename T>
  bool operator()(const T* const submap, const T* const node, T* residual) const {
    using std::cos;
    using std::sin;
    using std::atan2;
    const T c = cos(submap[2]), s = sin(submap[2]);
    const T dx = node[0] - submap[0], dy = node[1] - submap[1];
    const T x = c * dx + s * dy;  // the node in the submap's frame
    const T y = -s * dx + c * dy;
    const T angle = node[2] - submap[2] - T(measured_.theta);
    residual[0] = T(translation_weight_) * (x - T(measured_.x));
    residual[1] = T(translation_weight_) * (y - T(measured_.y));
    residual[2] = T(rotation_weight_) * atan2(sin(angle), cos(angle));
    return true;
  }

  static ceres::CostFunction* Create(const Pose2& measured, double translation_weight,
                                     double rotation_weight) {
    return new ceres::AutoDiffCostFunction<RelativePoseCost, 3, 3, 3>(
        new RelativePoseCost(measured, translation_weight, rotation_weight));
  }

 private:
  Pose2 measured_;
  double translation_weight_;
  double rotation_weight_;
};

std::array<double, 3> ToArray(const Pose2& p) { return {p.x, p.y, p.theta}; }

}  // namespace

std::vector<std::string> PoseGraphOptions::Validate() const {
  std::vector<std::string> errors;
  auto positive = [&errors](double v, const char* name) {
    if (!(v > 0.0 && std::isfinite(v))) errors.push_back(std::string(name) + " must be finite and > 0");
  };
  positive(local_translation_weight, "pose_graph_local_translation_weight");
  positive(local_rotation_weight, "pose_graph_local_rotation_weight");
  positive(loop_translation_weight, "loop_closure_translation_weight");
  positive(loop_rotation_weight, "loop_closure_rotation_weight");
  positive(consecutive_translation_weight, "pose_graph_consecutive_translation_weight");
  positive(consecutive_rotation_weight, "pose_graph_consecutive_rotation_weight");
  if (!(huber_scale >= 0.0 && std::isfinite(huber_scale))) {
    errors.push_back("loop_closure_huber_scale must be finite and >= 0");
  }
  if (max_num_iterations < 1) errors.push_back("pose_graph_max_num_iterations must be >= 1");
  return errors;
}

Eigen::Vector3d ConstraintResidual(const Constraint& constraint, const Pose2& submap,
                                   const Pose2& node, double translation_weight,
                                   double rotation_weight) {
  const std::array<double, 3> s = ToArray(submap), n = ToArray(node);
  Eigen::Vector3d r;
  RelativePoseCost(constraint.relative, translation_weight, rotation_weight)(s.data(), n.data(),
                                                                              r.data());
  return r;
}

PoseGraph::PoseGraph(const PoseGraphOptions& options) : options_(options) {}

int PoseGraph::AddSubmap(const Pose2& global_pose) {
  submaps_.push_back(global_pose);
  return static_cast<int>(submaps_.size()) - 1;
}

int PoseGraph::AddNode(const Pose2& global_pose) {
  nodes_.push_back(global_pose);
  return static_cast<int>(nodes_.size()) - 1;
}

void PoseGraph::AddConstraint(const Constraint& constraint) {
  if (constraint.submap < 0 || constraint.submap >= static_cast<int>(submaps_.size()) ||
      constraint.node < 0 || constraint.node >= static_cast<int>(nodes_.size())) {
    throw std::out_of_range("pose graph constraint between submap " +
                            std::to_string(constraint.submap) + " and node " +
                            std::to_string(constraint.node) + ", which do not both exist");
  }
  constraints_.push_back(constraint);
}

void PoseGraph::AddConsecutiveConstraint(const ConsecutiveConstraint& constraint) {
  const int n = static_cast<int>(nodes_.size());
  if (constraint.previous < 0 || constraint.previous >= n || constraint.next < 0 ||
      constraint.next >= n) {
    throw std::out_of_range("pose graph constraint between nodes " +
                            std::to_string(constraint.previous) + " and " +
                            std::to_string(constraint.next) + ", which do not both exist");
  }
  consecutive_.push_back(constraint);
}

OptimizationSummary PoseGraph::Optimize() {
  OptimizationSummary summary;
  if (submaps_.empty() || constraints_.empty()) {
    summary.solved = true;
    return summary;
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::array<double, 3>> submaps, nodes;
  for (const Pose2& p : submaps_) submaps.push_back(ToArray(p));
  for (const Pose2& p : nodes_) nodes.push_back(ToArray(p));

  ceres::Problem problem;
  for (const Constraint& c : constraints_) {
    const bool loop = c.tag == ConstraintTag::kLoop;
    ceres::LossFunction* loss =
        loop && options_.huber_scale > 0.0 ? new ceres::HuberLoss(options_.huber_scale) : nullptr;
    problem.AddResidualBlock(
        RelativePoseCost::Create(
            c.relative, loop ? options_.loop_translation_weight : options_.local_translation_weight,
            loop ? options_.loop_rotation_weight : options_.local_rotation_weight),
        loss, submaps[c.submap].data(), nodes[c.node].data());
  }
  for (const ConsecutiveConstraint& c : consecutive_) {
    problem.AddResidualBlock(
        RelativePoseCost::Create(c.relative, options_.consecutive_translation_weight,
                                 options_.consecutive_rotation_weight),
        nullptr, nodes[c.previous].data(), nodes[c.next].data());
  }
  if (problem.HasParameterBlock(submaps.front().data())) {
    problem.SetParameterBlockConstant(submaps.front().data());
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options_.max_num_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary report;
  ceres::Solve(solver, &problem, &report);

  summary.iterations = static_cast<int>(report.iterations.size());
  summary.initial_cost = report.initial_cost;
  summary.final_cost = report.final_cost;
  bool finite = true;
  for (const auto& p : submaps) finite = finite && std::isfinite(p[0] + p[1] + p[2]);
  for (const auto& p : nodes) finite = finite && std::isfinite(p[0] + p[1] + p[2]);
  summary.solved = report.IsSolutionUsable() && finite;
  if (summary.solved) {
    for (std::size_t i = 0; i < submaps.size(); ++i) {
      submaps_[i] = Pose2(submaps[i][0], submaps[i][1], NormalizeAngle(submaps[i][2]));
    }
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      nodes_[i] = Pose2(nodes[i][0], nodes[i][1], NormalizeAngle(nodes[i][2]));
    }
  } else {
    summary.message = finite ? report.BriefReport() : "a pose became non-finite";
  }
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace mapping
}  // namespace hex_slam
