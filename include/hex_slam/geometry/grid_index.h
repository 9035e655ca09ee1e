// Integer storage coordinates shared by every lattice: a cell's column and row in a dense array.
#ifndef HEX_SLAM_GEOMETRY_GRID_INDEX_H_
#define HEX_SLAM_GEOMETRY_GRID_INDEX_H_

#include <cmath>

namespace hex_slam {

struct GridIndex {
  int col = 0;
  int row = 0;
  bool operator==(const GridIndex& o) const { return col == o.col && row == o.row; }
  bool operator!=(const GridIndex& o) const { return !(*this == o); }
};

// floor(a / 2) for negative a too; gcc and C++20 define >> on negatives as arithmetic.
inline int FloorHalf(int a) { return a >> 1; }
static_assert((-3 >> 1) == -2, "arithmetic right shift required");

// Every cell index a coordinate can produce lies within ±kMaxCellIndex. No map reaches that far
// (map_max_cells is at most kMaxMapCells, so no side of storage is that long), and it is far
// enough inside int's range that the sums and differences of a few indices (hex distance, the
// third cube coordinate, neighbour steps) cannot overflow. A NaN, an infinity or 1e300 thus
// names a cell outside every map instead of being undefined behaviour.
constexpr int kMaxCellIndex = 1 << 28;

// x clamped to [-kMaxCellIndex, kMaxCellIndex], NaN to kMaxCellIndex: two compares, which gcc
// turns into two branches every in-range point predicts, cheap on the matcher's per-endpoint path.
inline double ClampToIndexRange(double x) {
  constexpr double kHi = kMaxCellIndex;
  x = x < kHi ? x : kHi;  // NaN fails the compare and becomes kHi
  return x > -kHi ? x : -kHi;
}

// floor(x) as an int, clamped as above. std::floor compiles to a dozen instructions on x86-64
// without SSE4.1 and the matchers call this for every endpoint; a truncation and a correction for
// negatives give the same integer in three.
inline int FloorToInt(double x) {
  x = ClampToIndexRange(x);
  const int truncated = static_cast<int>(x);
  return truncated - (x < truncated ? 1 : 0);
}

// ceil(x) as an int, clamped as above.
inline int CeilToInt(double x) { return -FloorToInt(-x); }

// The nearest integer (halves away from zero, as std::round), clamped as above.
inline int RoundToInt(double x) { return static_cast<int>(std::round(ClampToIndexRange(x))); }

}  // namespace hex_slam

#endif  // HEX_SLAM_GEOMETRY_GRID_INDEX_H_
