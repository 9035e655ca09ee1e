// The covariance a scan match publishes (poseupdate, scanmatch_odom): the match's residual
// variance over its Hessian, with each endpoint informing only along the surface it lies on.
//
// Why not the matcher's own Gauss–Newton Hessian as it is: a wall's cells on a lattice are not
// uniform along the wall (hexagons alternate rows; a wall off the lattice's axes crosses cells
// unevenly), so the interpolated map has a gradient along every wall, and ΣJᵀJ counts it as
// information. In a long featureless corridor the along-axis variance came out a third of the
// across one (hex) where it should be orders of magnitude larger, while the match slid 4–30 cm
// along it. A wall tells where the robot is across it, never along it: the information here is
// the matcher's, per endpoint, projected on the surface normal the scan shows at that endpoint.
#ifndef HEX_SLAM_MATCHING_MATCH_COVARIANCE_H_
#define HEX_SLAM_MATCHING_MATCH_COVARIANCE_H_

#include <vector>

#include <Eigen/Core>

#include "hex_slam/geometry/pose2.h"
#include "hex_slam/matching/scan_matcher.h"

namespace hex_slam {

// The covariance of the pose `match` found (m², rad²) for `points`, the matched endpoints in the
// base frame in scan order. An endpoint contributes only where its scan neighbours form a line
// (its normal is known); the map gradient's magnitude comes from the match's Hessian. Directions
// no endpoint constrains get kUnconstrainedVariance; with no usable endpoint, every direction.
Eigen::Matrix3d MatchCovariance(const MatchResult& match,
                                const std::vector<Eigen::Vector2d>& points);

// The covariance of a pose no scan measured (m², rad²): every direction unconstrained.
Eigen::Matrix3d UnknownPoseCovariance();

// Each point's unit surface normal in the points' frame: the normal of the straight run of
// consecutive points it belongs to (split-and-merge, in scan order); zero for a point in no run
// long enough (clutter, an isolated return).
std::vector<Eigen::Vector2d> SurfaceNormals(const std::vector<Eigen::Vector2d>& points);

}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_MATCH_COVARIANCE_H_
