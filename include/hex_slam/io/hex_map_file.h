// The native map file (.hexmap): every pyramid level's log-odds kept exactly, and the sub-cell
// hit means of the cells that were hit, so a saved map can be matched against again as it was
// (localization on a saved map). A map_server PGM keeps three values per square pixel and loses
// the lattice; this keeps the cells themselves.
//
// Layout, all little-endian:
//   "HEXSLAM\n" (8 bytes) | u32 format version | u32 lattice (0 hex, 1 square)
//   | f64 finest spacing (level k has spacing·2^k)
//   | f32 free_delta, occupied_delta, min_log_odds, max_log_odds
//   | u32 level count
//   | per level: i32 min_col, i32 min_row, i32 width, i32 height, f32 log_odds[width·height]
//                (version 2:) u32 hit cells h, h × (u32 cell, f32 mean_x, f32 mean_y, f32 count)
//   | (version 3:) the loop-closure graph, possibly empty:
//       u32 submaps S, S × (f64 local x, y, θ | f64 global x, y, θ | u32 k | u32 node ids[k])
//       u32 nodes N, N × (f64 stamp | f64 local x, y, θ | f64 global x, y, θ
//                         | f32 sensor x, y | u32 p | p × f32 x, y)
//       u32 constraints C, C × (u32 submap | u32 node | f64 x, y, θ | u32 tag | f32 score)
//   | u64 FNV-1a hash of every byte before it
// Version 1 files (no hit cells) are still read; their maps match without sub-cell offsets.
// Version 2 files (no graph) are read with an empty graph. A submap is kept as its frames and
// its nodes, not its cells: it is drawn again from them (mapping::Submap::FromNodes), as the
// loop-closure worker does with the finished submaps it drops.
// Sizes read from a file are checked against the caps and the bytes actually left before anything
// is allocated, so a corrupt header cannot make the reader allocate gigabytes.
#ifndef HEX_SLAM_IO_HEX_MAP_FILE_H_
#define HEX_SLAM_IO_HEX_MAP_FILE_H_

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hex_slam/geometry/grid_rect.h"
#include "hex_slam/io/atomic_file.h"
#include "hex_slam/map/map_pyramid.h"
#include "hex_slam/mapping/loop_closure/pose_graph.h"
#include "hex_slam/map/occupancy_model.h"
#include "hex_slam/mapping/slam.h"

namespace hex_slam {
namespace io {

constexpr std::uint32_t kHexMapFormatVersion = 3;
constexpr std::uint32_t kHexMapOldestVersion = 1;
constexpr int kHexMapMaxLevels = 8;  // SlamOptions allows map_multi_res_levels up to 8
constexpr std::int64_t kHexMapMaxCellsPerLevel = std::int64_t{1} << 28;  // 1 GiB of log-odds
// Storage indices stay far from int overflow when a rectangle's corners are added.
constexpr int kHexMapMaxAbsIndex = 1 << 28;
// The graph's caps: counts of submaps, nodes and constraints; points per node; and how far from
// the origin a pose or point may lie (m), far beyond any building.
constexpr std::int64_t kHexMapMaxGraphItems = std::int64_t{1} << 24;
constexpr std::int64_t kHexMapMaxNodePoints = std::int64_t{1} << 20;
constexpr double kHexMapMaxCoordinate = 1e7;

// One hit cell's CellHits: the running mean of the endpoints that fell in it, relative to its
// centre (m, world axes), and how many it holds (at most GridMap::kHitMemory).
struct HexMapHit {
  std::uint32_t cell = 0;  // row-major offset in the level's rectangle
  float mean_x = 0.0f;
  float mean_y = 0.0f;
  float count = 0.0f;
};

struct HexMapLevel {
  GridRect rect;
  std::vector<float> log_odds;  // row-major over rect, as GridMap::log_odds_grid()
  std::vector<HexMapHit> hits;  // the hit cells, by ascending offset
};

// The loop-closure graph at the latest optimisation (version 3).
struct HexMapSubmap {
  Pose2 local_pose;   // its frame in the front end's frame
  Pose2 global_pose;  // optimised
  std::vector<std::uint32_t> nodes;  // inserted into it, ascending ids
};
struct HexMapNode {
  double stamp = 0.0;
  Pose2 local_pose;   // the front end's
  Pose2 global_pose;  // optimised
  Eigen::Vector2f sensor_origin = Eigen::Vector2f::Zero();  // robot frame
  std::vector<Eigen::Vector2f> points;                      // robot frame
};
struct HexMapGraph {
  std::vector<HexMapSubmap> submaps;        // by id
  std::vector<HexMapNode> nodes;            // by id
  std::vector<mapping::Constraint> constraints;  // local and loop
  bool empty() const { return submaps.empty() && nodes.empty() && constraints.empty(); }
};

struct HexMapData {
  std::string lattice = "hex";  // "hex" or "square"
  double spacing = 0.0;          // of level 0, the finest
  OccupancyModel model;
  std::vector<HexMapLevel> levels;  // finest first
  HexMapGraph graph;                // empty without loop closure
};

// Written atomically. Returns an empty string or an error.
std::string WriteHexMapFile(const std::string& path, const HexMapData& map);
// The same as one file of a set written together (atomic_file.h).
void AddHexMapFile(const std::string& path, const HexMapData& map, AtomicFileSet* files);

// Returns an empty string, or an error saying what is wrong (bad magic, unsupported version,
// truncated, a size over the caps, a value breaking an invariant, a checksum mismatch, trailing
// bytes); `map` is left unchanged on error.
std::string ReadHexMapFile(const std::string& path, HexMapData* map);
// The same from a file's bytes; `path` names it in errors (the fuzz target's entry point).
std::string ParseHexMapFile(const std::string& bytes, const std::string& path, HexMapData* map);
// The checksum a file ends with: 64-bit FNV-1a of its first `count` bytes (all but the last 8).
std::uint64_t HexMapChecksum(const std::string& bytes, std::size_t count);

// Empty when `map` satisfies every invariant the reader checks; otherwise the first violation.
std::string CheckHexMapData(const HexMapData& map);

template <class Lattice>
HexMapData CaptureHexMap(const MapPyramid<Lattice>& maps) {
  HexMapData data;
  data.lattice = Lattice::kName;
  data.spacing = maps.level(0).lattice().spacing();
  data.model = maps.level(0).model();
  for (int k = 0; k < maps.size(); ++k) {
    const GridMap<Lattice>& grid = maps.level(k);
    HexMapLevel level{grid.rect(), grid.log_odds_grid().values(), {}};
    grid.log_odds_grid().ForEachWritten([&](std::size_t i, const GridIndex&) {
      const CellHits& hits = grid.HitsAt(i);
      if (hits.count <= 0.0f) return;
      const Eigen::Vector2f mean = hits.Mean();
      level.hits.push_back({static_cast<std::uint32_t>(i), mean.x(), mean.y(), hits.count});
    });
    data.levels.push_back(std::move(level));
  }
  return data;
}

// Replaces the contents of `maps` with `data`, which must have the same lattice, level count and
// spacing. Values are clamped to the receiving maps' own log-odds limits. Returns an empty string
// or an error (and then `maps` is unchanged).
template <class Lattice>
std::string RestoreHexMap(const HexMapData& data, MapPyramid<Lattice>* maps) {
  const std::string invalid = CheckHexMapData(data);
  if (!invalid.empty()) return invalid;
  if (data.lattice != Lattice::kName) {
    return "the map file holds a " + data.lattice + " map, not a " + Lattice::kName + " one";
  }
  if (static_cast<int>(data.levels.size()) != maps->size()) {
    return "the map file has " + std::to_string(data.levels.size()) + " levels, the map " +
           std::to_string(maps->size());
  }
  const double spacing = maps->level(0).lattice().spacing();
  constexpr double kSpacingTolerance = 1e-9;  // relative; the file stores the double exactly
  if (std::abs(data.spacing - spacing) > kSpacingTolerance * spacing) {
    return "the map file's spacing " + std::to_string(data.spacing) + " m differs from the map's " +
           std::to_string(spacing) + " m";
  }
  for (int k = 0; k < maps->size(); ++k) {
    GridMap<Lattice>& grid = maps->mutable_level(k);
    grid.Assign(data.levels[k].rect, data.levels[k].log_odds);
    for (const HexMapHit& h : data.levels[k].hits) {
      grid.SetHits(h.cell, Eigen::Vector2f(h.mean_x, h.mean_y), h.count);
    }
  }
  return "";
}

// The map of a running Slam, whichever its lattice; with loop closure also the graph of its
// latest solution (call Slam::FinishTrajectory first for the final one).
HexMapData CaptureSlamMap(const Slam& slam);

// The graph of a pose-graph solution.
HexMapGraph CaptureGraph(const mapping::PoseGraphSolution& solution);

// Localization on a saved map: fills `slam`'s map from `data` (as RestoreHexMap: same lattice,
// levels and spacing as its options give) and marks it loaded (Slam::UseLoadedMap). Returns an
// empty string or the error, `slam` unchanged then. The graph is not restored into the back end
// (a loaded map runs without loop closure).
std::string RestoreSlamMap(const HexMapData& data, Slam* slam);

// ReadHexMapFile then RestoreSlamMap; the error names the file.
std::string LoadSlamMap(const std::string& path, Slam* slam);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_HEX_MAP_FILE_H_
