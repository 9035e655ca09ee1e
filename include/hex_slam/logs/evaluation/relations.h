// The relations metric of Kümmerle et al., "On measuring the accuracy of SLAM algorithms"
// (Autonomous Robots, 2009): reference relative motions between pairs of times, each from the
// pose at t1 to the pose at t2 expressed in the t1 frame. For each relation the estimate's own
// motion between its poses at t1 and t2 is compared with it:
//   translational error = |(dx, dy)_estimated - (dx, dy)_reference|           (m)
//   rotational error    = |wrap(dyaw_estimated - dyaw_reference)|             (deg here)
// and the mean ± std of the errors and of their squares are reported. The poses at t1 and t2 are
// looked up as trajectory_lookup.h says (the same stamp, else interpolation across a short gap);
// relations without both poses are skipped and counted, never guessed.
#ifndef HEX_SLAM_LOGS_EVALUATION_RELATIONS_H_
#define HEX_SLAM_LOGS_EVALUATION_RELATIONS_H_

#include <string>
#include <vector>

#include "hex_slam/io/trajectory_io.h"
#include "hex_slam/logs/evaluation/sample_statistics.h"
#include "hex_slam/logs/evaluation/trajectory_lookup.h"
#include "hex_slam/geometry/pose2.h"

namespace hex_slam {
namespace logs {

struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Pose2 motion;  // from the pose at t1 to the pose at t2, in the t1 frame
};

// The Freiburg format: "t1 t2 dx dy dz roll pitch yaw" per line (dz, roll, pitch ignored).
// Returns an empty string or an error naming the bad line.
std::string ReadRelations(const std::string& path, std::vector<Relation>* relations);

struct RelationsOptions {
  double offset = 0.0;  // s added to the trajectory's stamps to bring them to the relations' clock
  LookupOptions lookup;
};

struct RelationsReport {
  int relations = 0;  // given
  int evaluated = 0;  // with both poses found
  SampleStatistics translation;          // m
  SampleStatistics translation_squared;  // m²
  SampleStatistics rotation;             // deg
  SampleStatistics rotation_squared;     // deg²
};

RelationsReport EvaluateRelations(const std::vector<io::StampedPose>& trajectory,
                                  const std::vector<Relation>& relations,
                                  const RelationsOptions& options);

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_EVALUATION_RELATIONS_H_
