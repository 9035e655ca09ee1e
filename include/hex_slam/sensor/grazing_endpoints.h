// Endpoints whose beam grazes the surface it hit, found from the scan alone.
//
// Such an endpoint tells where the surface is across it, but hardly where along it: a range
// error of σ moves it σ / cos(incidence) along the surface (5.8 σ at 80°), and neighbouring
// beams land far apart there, so the map holds the stretch as a row of dots (the hits of the
// few scans that saw it), with free or unknown cells between them. A scan taken a little
// farther along a straight wall puts its own grazing endpoints at the same beam angles, hence
// the same pattern shifted by the motion: matched against the dots, it is pulled back to
// where the last inserted scan was. In a corridor, where little else holds the scan along its
// axis, that stops the estimate dead (the simulated building's second lap without odometry).
#ifndef HEX_SLAM_SENSOR_GRAZING_ENDPOINTS_H_
#define HEX_SLAM_SENSOR_GRAZING_ENDPOINTS_H_

#include <vector>

#include <Eigen/Core>

namespace hex_slam {

// For each of `points` (sensor frame, scan order): true when it lies on a straight stretch of
// surface with its two scan neighbours (gaps on either side alike, itself on their chord) and
// its beam meets that stretch more than `max_incidence` (rad) from the surface normal. A point at
// a depth jump or a corner, and the first and last point, are never marked. max_incidence of
// π/2 or more marks none. Returns how many it marked.
int MarkGrazingEndpoints(const std::vector<Eigen::Vector2d>& points, double max_incidence,
                          std::vector<bool>* grazing);

}  // namespace hex_slam

#endif  // HEX_SLAM_SENSOR_GRAZING_ENDPOINTS_H_
