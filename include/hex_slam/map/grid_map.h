// A log-odds occupancy grid on any lattice (hex or square), stored densely and grown on demand.
//
// Cells live in one row-major rectangle of storage indices, 14 bytes each: the log-odds; the
// probability (kept beside them so the scan matcher's inner loop reads one float per cell and
// never calls exp()); a slot into the records of cells that were ever hit (a few percent of the
// cells, so the 16-byte hit records are not paid for by every cell); and a 16-bit scan stamp.
// Every array's zero means "unknown" (the probability is stored minus 0.5), so storage comes
// from zeroed pages that hold memory only once the robot has seen their cells.
// Member definitions are in grid_map.cpp, instantiated there for HexLattice and SquareLattice.
#ifndef HEX_SLAM_MAP_GRID_MAP_H_
#define HEX_SLAM_MAP_GRID_MAP_H_

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hex_slam/geometry/grid_rect.h"
#include "hex_slam/map/log_odds_grid.h"
#include "hex_slam/map/occupancy_model.h"
#include "hex_slam/map/zeroed_array.h"

namespace hex_slam {

// Where in a cell the endpoints that hit it fell: the running mean of their positions relative
// to the cell's centre (m, world axes). A wall lies anywhere inside its cells, but the matcher,
// pulling endpoints to the interpolated occupancy's peak, would put it at their centres: a bias
// of up to half a cell per wall. With these offsets it puts the wall where it was seen.
//
// Stored as the terms the matcher sums, so its sub-cell read is one 16-byte load per cell and
// a blend of four of them, with no branch and no second array: `weight` is the cell's pull on a
// stencil's mean offset (its occupancy probability once hit, so free and never-hit cells do not
// pull; 0 before), and (x, y) is that weight times the mean offset.
struct alignas(16) CellHits {
  float weight = 0.0f;
  float x = 0.0f;
  float y = 0.0f;
  float count = 0.0f;  // hits in the running mean (capped); 0 for a cell never hit

  // The running mean itself (m); zero for a cell never hit.
  Eigen::Vector2f Mean() const {
    return count > 0.0f ? Eigen::Vector2f(x / weight, y / weight) : Eigen::Vector2f::Zero();
  }
};
static_assert(sizeof(CellHits) == 16, "a cell's hit record is one aligned 16-byte load");

// A hit cell's weight never falls below this, however free the cell has become, so its mean can
// always be read back from the weighted terms. It is far below any weight that moves a stencil.
constexpr float kMinCellHitWeight = 1e-20f;
// Below this total weight a stencil's hits count as none.
constexpr float kMinHitWeight = 1e-6f;

// A cell's hit record: `records` indexed by the cell's slot (slot 0 is the all-zero record of the
// cells never hit, so readers need no branch).
inline const CellHits& HitRecord(const CellHits* records, const std::uint32_t* slots,
                                 std::size_t offset) {
  return records[slots[offset]];
}

// The mean hit offset of an interpolation stencil: its `n` cells (storage offsets) averaged with
// their interpolation weights times their CellHits::weight. False, and `mean` untouched, when the
// stencil's hits weigh (next to) nothing.
inline bool MeanHitOffset(const CellHits* records, const std::uint32_t* slots,
                          const std::size_t* cells, const double* weights, int n,
                          Eigen::Vector2d* mean) {
  double total = 0.0, sx = 0.0, sy = 0.0;
  for (int k = 0; k < n; ++k) {
    const CellHits& h = HitRecord(records, slots, cells[k]);
    total += weights[k] * h.weight;
    sx += weights[k] * h.x;
    sy += weights[k] * h.y;
  }
  if (total <= kMinHitWeight) return false;
  *mean = Eigen::Vector2d(sx / total, sy / total);
  return true;
}

struct GridGrowthPolicy {
  bool auto_grow = true;
  // Storage never grows past this many cells; points beyond it are counted and skipped.
  std::int64_t max_cells = std::int64_t{1} << 26;
  // Each growth adds at least this fraction of the current size on the side that needed it, so
  // a robot driving away from the origin causes O(log n) reallocations.
  double min_growth_fraction = 0.5;
  // Cells kept between a scan's endpoints and the storage edge after a growth.
  int margin_cells = 16;
  // Storage takes its memory when allocated rather than where first written (Paging): for grids
  // sized to what they will hold, such as submaps; a map sized for the whole building keeps it
  // lazy.
  bool prefault = false;
};

template <class Lattice>
class GridMap {
 public:
  using Cell = typename Lattice::Cell;
  static constexpr float kUnknownProbability = 0.5f;

  GridMap(const Lattice& lattice, const OccupancyModel& model, const GridGrowthPolicy& growth,
          const Eigen::AlignedBox2d& initial_extent);

  const Lattice& lattice() const { return log_odds_.lattice(); }
  const OccupancyModel& model() const { return model_; }
  const GridRect& rect() const { return log_odds_.rect(); }
  // The log-odds alone (what readers that copy or rasterise the map need).
  const LogOddsGrid<Lattice>& log_odds_grid() const { return log_odds_; }

  float ProbabilityAt(const GridIndex& index) const {
    return kUnknownProbability + CentredAt(index);
  }
  float Probability(const Cell& cell) const { return ProbabilityAt(Lattice::ToIndex(cell)); }
  // The cell's entry of centred_probabilities(), 0 (unknown) outside storage: for readers that
  // must give the same number at the storage's edge as inside it.
  float CentredAt(const GridIndex& index) const {
    return rect().Contains(index) ? centred_[rect().Offset(index)] : 0.0f;
  }
  // The cell's entry of hit_slots(), 0 (never hit) outside storage.
  std::uint32_t HitSlotAt(const GridIndex& index) const {
    return rect().Contains(index) ? hit_slot_[rect().Offset(index)] : 0;
  }
  float LogOddsAt(const GridIndex& index) const { return log_odds_.LogOddsAt(index); }
  float LogOdds(const Cell& cell) const { return log_odds_.LogOdds(cell); }
  bool IsKnownAt(const GridIndex& index) const { return log_odds_.IsKnownAt(index); }

  // Row-major arrays over rect(), for the matchers' inner loops: the occupancy probability minus
  // kUnknownProbability, and each cell's slot in hit_records() (0: never hit).
  const float* centred_probabilities() const { return centred_.data(); }
  const std::uint32_t* hit_slots() const { return hit_slot_.data(); }
  const CellHits* hit_records() const { return hit_records_.data(); }
  // The hit record of the cell at storage `offset` (all zero if never hit).
  const CellHits& HitsAt(std::size_t offset) const {
    return HitRecord(hit_records_.data(), hit_slot_.data(), offset);
  }
  // Cells that were ever hit.
  std::size_t hit_cells() const { return hit_records_.size() - 1; }
  // The running mean of a cell's hits forgets older ones beyond this many, so a wall that moved
  // is relearnt.
  static constexpr float kHitMemory = 64.0f;

  // One scan's update (MATH.md §7): every cell a beam crosses before its endpoint cell gets the
  // free increment, every endpoint cell the occupied one, each cell at most once per scan, and
  // "occupied" wins over "free" whatever the beam order; every endpoint joins its cell's hit
  // mean. Grows storage first if allowed.
  void InsertScan(const Eigen::Vector2d& origin, const std::vector<Eigen::Vector2d>& endpoints);

  // Makes sure storage covers `box` (subject to the growth policy). Returns false if capped.
  bool EnsureCovers(const Eigen::AlignedBox2d& box);
  // Storage over `box` as well, exactly (no growth margin; counted as no growth), unless that
  // would exceed growth.max_cells: returns false then, and the storage is unchanged.
  bool Reserve(const Eigen::AlignedBox2d& box);
  // Storage cut down to the cells ever written (LogOddsGrid::written); none if none was, and
  // the state only insertion needs let go. For a map that will not grow again: its reads are
  // unchanged (a later InsertScan still works, drawing that state again).
  void ShrinkToWritten();

  // Forgets every observation; keeps the storage extent.
  void Clear();
  // Replaces the contents, e.g. from a map file (without hit offsets). `log_odds` must have
  // rect.size() entries.
  void Assign(const GridRect& rect, const std::vector<float>& log_odds);
  // Gives cell `offset` the hit record of a map file: `count` hits whose mean offset from the
  // centre is `mean` (m). count must be in (0, kHitMemory].
  void SetHits(std::size_t offset, const Eigen::Vector2f& mean, float count);

  // World box covered by storage, and by cells that have been observed at least once.
  Eigen::AlignedBox2d StorageExtent() const { return log_odds_.StorageExtent(); }
  Eigen::AlignedBox2d KnownExtent() const { return log_odds_.KnownExtent(); }
  // Bytes of storage that hold memory: the written part of every array (all of it, prefaulted),
  // and the hit records.
  std::size_t MemoryBytes() const;
  // Endpoints and rays skipped because the growth cap was reached.
  std::int64_t points_outside() const { return points_outside_; }
  int growth_count() const { return growth_count_; }

 private:
  static constexpr std::size_t kBytesPerCell =
      sizeof(float) * 2 + sizeof(std::uint32_t) + sizeof(std::uint16_t);

  void Resize(const GridRect& rect);
  Paging paging() const { return growth_.prefault ? Paging::kAtAllocation : Paging::kOnFirstWrite; }
  void MarkFree(std::size_t offset);
  void MarkOccupied(std::size_t offset);
  void AddHit(std::size_t offset, const Eigen::Vector2d& relative);
  // A hit cell's weighted terms after its probability changed.
  static void Reweigh(CellHits* h, float probability);
  void SetLogOdds(std::size_t offset, float value);
  // Zeroed stamps over the storage again, after ShrinkToWritten let them go or Clear.
  void RestoreStamps();
  // False after ShrinkToWritten let the stamps go, until the next insertion draws them again.
  bool stamps_held() const { return stamp_.size() == rect().size(); }
  void NextStamps();
  void ResetHitRecords();

  OccupancyModel model_;
  GridGrowthPolicy growth_;
  LogOddsGrid<Lattice> log_odds_;  // the lattice, the storage rectangle and the log-odds
  ZeroedArray<float> centred_;     // probability - kUnknownProbability
  ZeroedArray<std::uint32_t> hit_slot_;
  std::vector<CellHits> hit_records_;  // [0]: the record of every cell never hit
  // Per-cell scan stamp: equals free_stamp_ if this scan freed it, occupied_stamp_ if it hit it.
  ZeroedArray<std::uint16_t> stamp_;
  std::uint16_t free_stamp_ = 0;
  std::uint16_t occupied_stamp_ = 1;
  std::int64_t points_outside_ = 0;
  int growth_count_ = 0;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_GRID_MAP_H_
