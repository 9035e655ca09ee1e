#include "map_output/hex_map_marker.h"

#include <array>
#include <cmath>

namespace hex_slam {
namespace node {
namespace {

constexpr int kHexCorners = 6;
constexpr int kSquareCorners = 4;

// Corners of a cell of unit scale, counter-clockwise, relative to its centre. The hex lattice's
// cells are flat-topped (neighbours straight up and down, MATH.md §2): corners at 0°, 60°, ...,
// at the circumradius d/sqrt(3).
std::array<Eigen::Vector2d, kHexCorners> CellCorners(const HexLattice& lattice) {
  std::array<Eigen::Vector2d, kHexCorners> corners;
  const double radius = lattice.spacing() / std::sqrt(3.0);
  for (int k = 0; k < kHexCorners; ++k) {
    const double angle = k * M_PI / 3.0;
    corners[k] = radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  return corners;
}

std::array<Eigen::Vector2d, kSquareCorners> CellCorners(const SquareLattice& lattice) {
  const double h = 0.5 * lattice.spacing();
  return {Eigen::Vector2d(-h, -h), Eigen::Vector2d(h, -h), Eigen::Vector2d(h, h),
          Eigen::Vector2d(-h, h)};
}

template <class Lattice>
void DrawCells(const LogOddsGrid<Lattice>& grid, const MarkerStyle& style,
               visualization_msgs::Marker* marker, MarkerStats* stats) {
  auto corners = CellCorners(grid.lattice());
  for (Eigen::Vector2d& c : corners) c *= style.cell_scale;
  grid.ForEachKnown([&](std::size_t, const GridIndex& index, float log_odds) {
    if (stats->known_cells++ >= style.max_cells) return;
    ++stats->drawn_cells;
    const Eigen::Vector2d centre = grid.lattice().CentreOf(index);
    std_msgs::ColorRGBA colour;
    colour.r = colour.g = colour.b = 1.0f - OccupancyModel::Probability(log_odds);
    colour.a = 1.0f;
    // A fan from the first corner: n - 2 triangles.
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      for (const Eigen::Vector2d* corner : {&corners[0], &corners[k], &corners[k + 1]}) {
        geometry_msgs::Point p;
        p.x = centre.x() + corner->x();
        p.y = centre.y() + corner->y();
        p.z = style.height;
        marker->points.push_back(p);
        marker->colors.push_back(colour);
      }
    }
  });
}

}  // namespace

template <class Lattice>
visualization_msgs::Marker MakeHexMapMarker(const LogOddsGrid<Lattice>& grid,
                                            const MarkerStyle& style, const std::string& frame,
                                            const ros::Time& stamp, MarkerStats* stats) {
  *stats = MarkerStats();
  visualization_msgs::Marker marker;
  marker.header.frame_id = frame;
  marker.header.stamp = stamp;
  marker.ns = "hex_map";
  marker.id = 0;
  marker.type = visualization_msgs::Marker::TRIANGLE_LIST;
  marker.pose.orientation.w = 1.0;
  marker.scale.x = marker.scale.y = marker.scale.z = 1.0;
  marker.color.r = marker.color.g = marker.color.b = marker.color.a = 1.0f;
  DrawCells(grid, style, &marker, stats);
  // An empty triangle list is an error in rviz; an empty map deletes the marker instead.
  marker.action = marker.points.empty() ? visualization_msgs::Marker::DELETE
                                        : visualization_msgs::Marker::ADD;
  return marker;
}

template visualization_msgs::Marker MakeHexMapMarker(const LogOddsGrid<HexLattice>&,
                                                     const MarkerStyle&, const std::string&,
                                                     const ros::Time&, MarkerStats*);
template visualization_msgs::Marker MakeHexMapMarker(const LogOddsGrid<SquareLattice>&,
                                                     const MarkerStyle&, const std::string&,
                                                     const ros::Time&, MarkerStats*);

visualization_msgs::Marker MakeHexMapMarker(const MapSnapshot& snapshot, const MarkerStyle& style,
                                            const std::string& frame, const ros::Time& stamp,
                                            MarkerStats* stats) {
  return snapshot.hex ? MakeHexMapMarker(snapshot.hex->drawn(), style, frame, stamp, stats)
                      : MakeHexMapMarker(snapshot.square->drawn(), style, frame, stamp, stats);
}

}  // namespace node
}  // namespace hex_slam
