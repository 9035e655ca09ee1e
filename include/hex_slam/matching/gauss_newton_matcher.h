// The Gauss–Newton scan matcher of each lattice (the front end's), for code written over the
// lattice that refines a pose on a map pyramid.
#ifndef HEX_SLAM_MATCHING_GAUSS_NEWTON_MATCHER_H_
#define HEX_SLAM_MATCHING_GAUSS_NEWTON_MATCHER_H_

// Both, for ScanMatcherTraits of each lattice.
#include "hex_slam/matching/hex_scan_matcher.h"
#include "hex_slam/matching/square_scan_matcher.h"

namespace hex_slam {
namespace matching {

template <class Lattice>
using GaussNewtonMatcher = ScanMatcher<Lattice>;

}  // namespace matching
}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_GAUSS_NEWTON_MATCHER_H_
