// The bounds of branch and bound: a map's cell values max-pooled over windows of 2^k × 2^k cells
// in lattice coordinates (LatticeAxes; on the hex lattice the windows are axial parallelograms),
// one grid per depth k, as Cartographer's precomputation grids. Depth k at z holds the largest
// value of the cells z + [0, 2^k)², so a scan scored on depth k at offset δ scores at least as
// much as at any offset of δ + [0, 2^k)² on depth 0: an upper bound for that whole block of
// candidates.
#ifndef HEX_SLAM_MATCHING_PRECOMPUTATION_GRID_H_
#define HEX_SLAM_MATCHING_PRECOMPUTATION_GRID_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/map/grid_map.h"

namespace hex_slam {
namespace matching {

// Values are stored as bytes, as in Cartographer's grids: a probability p as round(255 p). A
// submap's grids hold its map once per depth: as floats they took four times the memory (on
// Intel the worker's cache of submaps and grids is 91 MB with bytes, 124 MB with floats) and the
// searches read four times the bytes. A score moves by at most 1/510 for it, far below what
// separates a match from the next candidate.
constexpr float kValueScale = 255.0f;
inline std::uint8_t QuantizeValue(float probability) {
  if (!(probability > 0.0f)) return 0;
  return static_cast<std::uint8_t>(std::lround(std::min(probability, 1.0f) * kValueScale));
}
// The probability a code stands for, exactly (a score is a mean of these).
inline double DequantizeValue(std::uint8_t code) { return static_cast<double>(code) / kValueScale; }
// What a grid holds for `probability`.
inline double QuantizedProbability(float probability) {
  return DequantizeValue(QuantizeValue(probability));
}
// The smallest code that stands for at least `probability` (in [0, 1]): a grid built of these
// bounds every value it was built from exactly, not to within rounding.
inline std::uint8_t QuantizeValueUp(float probability) {
  if (!(probability > 0.0f)) return 0;
  // 255 p is exact in double (p has 24 significant bits), so its ceiling is the code.
  return static_cast<std::uint8_t>(
      std::ceil(std::min(static_cast<double>(probability), 1.0) * kValueScale));
}

// One depth: dense values over a box of lattice coordinates; every cell outside it has
// `outside`, the value of a window that sees no known cell.
class PrecomputationGrid {
 public:
  PrecomputationGrid(const Eigen::Array2i& origin, const Eigen::Array2i& size, float outside);

  // The stored value at z (QuantizedProbability of what was set).
  float At(const Eigen::Array2i& z) const { return static_cast<float>(DequantizeValue(CodeAt(z))); }
  std::uint8_t CodeAt(const Eigen::Array2i& z) const {
    const Eigen::Array2i local = z - origin_;
    if (static_cast<unsigned>(local.x()) >= static_cast<unsigned>(size_.x()) ||
        static_cast<unsigned>(local.y()) >= static_cast<unsigned>(size_.y())) {
      return outside_;
    }
    return values_[static_cast<std::size_t>(local.y()) * size_.x() + local.x()];
  }
  void Set(const Eigen::Array2i& z, float value) { values_[IndexOf(z)] = QuantizeValue(value); }
  // Every stored value down to zero (cells outside keep `outside`).
  void Clear() { std::fill(values_.begin(), values_.end(), std::uint8_t{0}); }
  // Row y's codes from x_from on raised to at least codes[0], codes[1], ... codes[count - 1]
  // (all inside the box; codes from QuantizeValueUp make a grid of bounds).
  void RaiseRow(int y, int x_from, const std::uint8_t* codes, int count) {
    std::uint8_t* row = values_.data() + IndexOf({x_from, y});
    for (int i = 0; i < count; ++i) row[i] = std::max(row[i], codes[i]);
  }

  // Whether every cell of the box [lowest, highest] is stored (At reads none outside).
  bool Contains(const Eigen::Array2i& lowest, const Eigen::Array2i& highest) const {
    return (lowest >= origin_).all() && (highest < origin_ + size_).all();
  }
  // Row-major codes: CodeAt(z) for z in the box is data()[(z - origin).y * size.x + (z - origin).x].
  const std::uint8_t* data() const { return values_.data(); }

  const Eigen::Array2i& origin() const { return origin_; }
  const Eigen::Array2i& size() const { return size_; }
  // The last coordinates inside the box.
  Eigen::Array2i last() const { return origin_ + size_ - 1; }
  float outside() const { return static_cast<float>(DequantizeValue(outside_)); }
  std::size_t MemoryBytes() const { return values_.size() * sizeof(values_[0]); }

  // Depth k + 1 from depth k (windows of `half` = 2^k cells): the maximum of four shifted reads.
  PrecomputationGrid Doubled(int half) const;

 private:
  // Only for z inside the box.
  std::size_t IndexOf(const Eigen::Array2i& z) const {
    const Eigen::Array2i local = z - origin_;
    return static_cast<std::size_t>(local.y()) * size_.x() + local.x();
  }

  Eigen::Array2i origin_;
  Eigen::Array2i size_;
  std::uint8_t outside_;
  std::vector<std::uint8_t> values_;
};

// Every depth from 0 (the cell values themselves) to max_depth.
class PrecomputationGridStack {
 public:
  // Cell value: the occupancy probability of a known cell, `unknown_value` for one never seen
  // (and for everything beyond the map).
  template <class Lattice>
  PrecomputationGridStack(const GridMap<Lattice>& grid, int max_depth, float unknown_value);
  // Depths 1 to max_depth max-pooled from `cells`, which becomes depth 0.
  PrecomputationGridStack(PrecomputationGrid cells, int max_depth);

  int max_depth() const { return static_cast<int>(grids_.size()) - 1; }
  const PrecomputationGrid& Get(int depth) const { return grids_[depth]; }
  // The box of known cells (depth 0); empty (size 0) for a map with none.
  const PrecomputationGrid& cells() const { return grids_.front(); }
  std::size_t MemoryBytes() const;

 private:
  std::vector<PrecomputationGrid> grids_;
};

}  // namespace matching
}  // namespace hex_slam

#endif  // HEX_SLAM_MATCHING_PRECOMPUTATION_GRID_H_
