// libFuzzer target: .hexmap file bytes, parsed as hex_slam_offline --map and the node's map_file
// read them. A map that parses is restored into a map pyramid (as localization does) and must
// come back out cell for cell; on hexagons a path is planned on it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_check.h"
#include "hex_slam/planning/hex_planner.h"
#include "hex_slam/io/hex_map_file.h"

namespace {

// Restores only maps this small: a valid file may describe billions of cells.
constexpr std::size_t kMaxRestoredCells = std::size_t{1} << 18;

template <class Lattice>
hex_slam::MapPyramid<Lattice> Restored(const hex_slam::io::HexMapData& data) {
  hex_slam::GridGrowthPolicy growth;
  growth.auto_grow = false;
  const Eigen::Vector2d one(data.spacing, data.spacing);
  hex_slam::MapPyramid<Lattice> maps(data.spacing, static_cast<int>(data.levels.size()),
                                     data.model, growth, Eigen::AlignedBox2d(-one, one));
  HEX_SLAM_FUZZ_CHECK(hex_slam::io::RestoreHexMap(data, &maps).empty());
  const hex_slam::io::HexMapData again = hex_slam::io::CaptureHexMap(maps);
  HEX_SLAM_FUZZ_CHECK(again.levels.size() == data.levels.size());
  for (std::size_t k = 0; k < data.levels.size(); ++k) {
    HEX_SLAM_FUZZ_CHECK(again.levels[k].log_odds == data.levels[k].log_odds);
    HEX_SLAM_FUZZ_CHECK(again.levels[k].hits.size() == data.levels[k].hits.size());
  }
  return maps;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hex_slam;
  io::HexMapData map;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  // A mutation almost never keeps the checksum right, so for even sizes it is put right here:
  // the parser's checks behind it are what is fuzzed. Odd sizes keep the checksum test itself.
  if (size >= sizeof(std::uint64_t) && size % 2 == 0) {
    const std::size_t hashed = size - sizeof(std::uint64_t);
    const std::uint64_t hash = io::HexMapChecksum(bytes, hashed);
    for (std::size_t i = 0; i < sizeof hash; ++i) {
      bytes[hashed + i] = static_cast<char>((hash >> (8 * i)) & 0xff);  // little-endian, as written
    }
  }
  if (!io::ParseHexMapFile(bytes, "fuzz", &map).empty()) return 0;
  HEX_SLAM_FUZZ_CHECK(io::CheckHexMapData(map).empty());
  std::size_t cells = 0;
  for (const io::HexMapLevel& level : map.levels) cells += level.rect.size();
  if (cells > kMaxRestoredCells) return 0;
  if (map.lattice == "square") {
    Restored<SquareLattice>(map);
    return 0;
  }
  const MapPyramid<HexLattice> maps = Restored<HexLattice>(map);
  const GridMap<HexLattice>& finest = maps.level(0);
  const Eigen::AlignedBox2d extent = finest.StorageExtent();
  PlanHexPath(finest.log_odds_grid(), extent.min(), extent.max(), HexPlannerOptions());
  PlanHexPath(finest.log_odds_grid(), extent.center(), extent.max(), HexPlannerOptions());
  return 0;
}
