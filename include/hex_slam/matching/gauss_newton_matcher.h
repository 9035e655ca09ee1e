// The Gauss–Newton scan matcher of each lattice (the front end's), for code written over the
// lattice that refines a pose on a map pyramid.
#ifndef HEX_SLAM_MATCHING_GAUSS_NEWTON_MATCHER_H_
#define HEX_SLAM_MATCHING_GAUSS_NEWTON_MATCHER_H_

#include "hex_slam/hex_scan_matcher.h"
#include "hex_slam/square_scan_matcher.h"

namespace hex_slam {
namespace matching {

template <class Lattice>
struct GaussNewtonMatcherOf;
template <>
struct GaussNewtonMatcherOf<HexLattice> {
  using type = HexScanMatcher;
};
template <>
struct GaussNewtonMatcherOf<SquareLattice> {
  using type = SquareScanMatcher;
};
template <class Lattice>
using GaussNewtonMatcher = typename GaussNewtonMatcherOf<Lattice>::type;

}  // namespace matching
}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_GAUSS_NEWTON_MATCHER_H_
