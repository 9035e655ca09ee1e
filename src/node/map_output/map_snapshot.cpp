#include "map_output/map_snapshot.h"

#include <algorithm>

namespace hex_slam {
namespace node {
namespace {

// Cells of slack around the changed box: a ray's cells reach a cell past its end points.
constexpr int kChangedMargin = 2;

template <class Lattice>
void CopyLevel(const GridMap<Lattice>& level, const Eigen::AlignedBox2d& changed, bool all,
               LogOddsGrid<Lattice>* copy) {
  GridRect region;
  if (!changed.isEmpty()) {
    GridIndex lo, hi;
    level.lattice().IndexBounds(changed, &lo, &hi);
    region = GridRect::FromCorners(lo, hi).Grown(kChangedMargin);
  }
  copy->CopyFrom(level.log_odds_grid(), region, all);
}

template <class Lattice>
io::OccupancyRaster RasterizeGrid(const LogOddsGrid<Lattice>& grid, double resolution) {
  io::OccupancyRaster raster = io::Rasterize(grid, resolution);
  return raster.data.empty() ? io::EmptyRaster(resolution) : raster;
}

template <class Lattice>
void Refresh(const MapPyramid<Lattice>* maps, const Eigen::AlignedBox2d& changed, bool all,
             int drawn_level, std::optional<PyramidCopy<Lattice>>* copy) {
  if (maps == nullptr) {
    copy->reset();
    return;
  }
  if (!*copy) {
    copy->emplace(*maps, drawn_level);
    all = true;
  }
  (*copy)->Refresh(*maps, changed, all);
}

}  // namespace

template <class Lattice>
PyramidCopy<Lattice>::PyramidCopy(const MapPyramid<Lattice>& maps, int drawn_level)
    : drawn_level_(std::clamp(drawn_level, 0, maps.size() - 1)),
      finest_(maps.level(0).lattice()),
      drawn_(maps.level(drawn_level_).lattice()) {}

template <class Lattice>
void PyramidCopy<Lattice>::Refresh(const MapPyramid<Lattice>& maps,
                                   const Eigen::AlignedBox2d& changed, bool all) {
  CopyLevel(maps.level(0), changed, all, &finest_);
  if (drawn_level_ > 0) CopyLevel(maps.level(drawn_level_), changed, all, &drawn_);
}

template class PyramidCopy<HexLattice>;
template class PyramidCopy<SquareLattice>;

void UpdateSnapshot(const Slam& slam, const Eigen::AlignedBox2d& changed, bool all,
                     std::uint64_t generation, int drawn_level, MapSnapshot* snapshot) {
  UpdateSnapshot(slam.hex_maps(), slam.square_maps(), changed, all, generation, drawn_level,
                 snapshot);
}

void UpdateSnapshot(const MapPyramid<HexLattice>* hex, const MapPyramid<SquareLattice>* square,
                    const Eigen::AlignedBox2d& changed, bool all, std::uint64_t generation,
                    int drawn_level, MapSnapshot* snapshot) {
  Refresh(hex, changed, all, drawn_level, &snapshot->hex);
  Refresh(square, changed, all, drawn_level, &snapshot->square);
  snapshot->generation = generation;
}

io::OccupancyRaster RasterizeSnapshot(const MapSnapshot& snapshot, double resolution) {
  return snapshot.hex ? RasterizeGrid(snapshot.hex->finest(), resolution)
                      : RasterizeGrid(snapshot.square->finest(), resolution);
}

}  // namespace node
}  // namespace hex_slam
