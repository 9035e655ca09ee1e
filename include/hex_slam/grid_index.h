// Integer storage coordinates shared by every lattice: a cell's column and row in a dense array.
#ifndef HEX_SLAM_GRID_INDEX_H_
#define HEX_SLAM_GRID_INDEX_H_

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

// floor(x) as an int, for |x| < 2^31 (map coordinates in cells always are). std::floor compiles to
// a dozen instructions on x86-64 without SSE4.1 and the matchers call it for every endpoint; a
// truncation and a correction for negatives give the same integer in three.
inline int FloorToInt(double x) {
  const int truncated = static_cast<int>(x);
  return truncated - (x < truncated ? 1 : 0);
}

}  // namespace hex_slam

#endif  // HEX_SLAM_GRID_INDEX_H_
