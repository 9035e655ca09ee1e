#include "hex_slam/logs/evaluation/relations.h"

#include <cmath>

#include "hex_slam/common/input_limits.h"
#include "hex_slam/io/number_rows.h"

namespace hex_slam {
namespace logs {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

}  // namespace

std::string ReadRelations(const std::string& path, std::vector<Relation>* relations) {
  relations->clear();
  return io::ReadNumberRows(path, 8, "t1 t2 dx dy dz roll pitch yaw", [relations](const double* v) {
    const Relation r{v[0], v[1], Pose2(v[2], v[3], v[7])};
    std::string error = CheckStamp(r.t1, "t1");
    if (error.empty()) error = CheckStamp(r.t2, "t2");
    if (error.empty()) error = CheckPose(r.motion, "motion (dx dy yaw)");
    if (error.empty()) relations->push_back(r);
    return error;
  });
}

RelationsReport EvaluateRelations(const std::vector<io::StampedPose>& trajectory,
                                  const std::vector<Relation>& relations,
                                  const RelationsOptions& options) {
  std::vector<io::StampedPose> shifted = trajectory;
  for (io::StampedPose& p : shifted) p.stamp += options.offset;
  const TrajectoryLookup lookup(std::move(shifted));
  std::vector<double> translation, translation_sq, rotation, rotation_sq;
  for (const Relation& r : relations) {
    const std::optional<Pose2> a = lookup.At(r.t1, options.lookup);
    const std::optional<Pose2> b = a ? lookup.At(r.t2, options.lookup) : std::nullopt;
    if (!b) continue;
    const Pose2 estimated = RelativePose(*a, *b);
    const double e_t = (estimated.translation() - r.motion.translation()).norm();
    const double e_r =
        std::abs(NormalizeAngle(estimated.theta - r.motion.theta)) * kDegreesPerRadian;
    translation.push_back(e_t);
    translation_sq.push_back(e_t * e_t);
    rotation.push_back(e_r);
    rotation_sq.push_back(e_r * e_r);
  }
  RelationsReport report;
  report.relations = static_cast<int>(relations.size());
  report.evaluated = static_cast<int>(translation.size());
  report.translation = Summarize(std::move(translation));
  report.translation_squared = Summarize(std::move(translation_sq));
  report.rotation = Summarize(std::move(rotation));
  report.rotation_squared = Summarize(std::move(rotation_sq));
  return report;
}

}  // namespace logs
}  // namespace hex_slam
