// Paging is checked against the kernel's own account of which pages are resident (mincore).
#include "hex_slam/map/zeroed_array.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/map/grid_map.h"
#include "hex_slam/map/hex_grid.h"
#include "hex_slam/map/square_grid.h"

namespace hex_slam {
namespace {

// 4 MB of floats: mapped pages, not the heap (ZeroedArray maps from 1 MB).
constexpr std::size_t kLargeFloats = std::size_t{1} << 20;

// The fraction of the pages under [data, data + bytes) that hold memory.
double ResidentFraction(const void* data, std::size_t bytes) {
  const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const std::size_t pages = (bytes + page - 1) / page;
  std::vector<unsigned char> resident(pages);
  if (mincore(const_cast<void*>(data), bytes, resident.data()) != 0) return -1.0;
  std::size_t count = 0;
  for (unsigned char r : resident) count += r & 1u;
  return static_cast<double>(count) / static_cast<double>(pages);
}

// Whether this kernel can populate a mapping up front (Linux 5.14 on); before, kAtAllocation
// pages fault lazily, as documented.
bool KernelPopulates() {
  const std::size_t bytes = std::size_t{1} << 16;
  void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) return false;
  const bool ok = madvise(m, bytes, MADV_POPULATE_WRITE) == 0;
  munmap(m, bytes);
  return ok;
}

TEST(ZeroedArrayTest, LazyPagesHoldMemoryOnlyWhereWritten) {
  ZeroedArray<float> lazy(kLargeFloats);
  EXPECT_EQ(lazy.paging(), Paging::kOnFirstWrite);
  // Huge pages may make a write resident in 2 MB at once: half the array stays unbacked.
  EXPECT_LT(ResidentFraction(lazy.data(), kLargeFloats * sizeof(float)), 0.5);
  lazy[0] = 1.0f;
  EXPECT_GT(ResidentFraction(lazy.data(), kLargeFloats * sizeof(float)), 0.0);
}

TEST(ZeroedArrayTest, PagesAtAllocationAreResidentAndZero) {
  if (!KernelPopulates()) GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE (Linux < 5.14)";
  ZeroedArray<float> eager(kLargeFloats, Paging::kAtAllocation);
  EXPECT_EQ(ResidentFraction(eager.data(), kLargeFloats * sizeof(float)), 1.0);
  for (float v : eager) ASSERT_EQ(v, 0.0f);
  // What is made from it keeps its paging: a reset, a copy.
  eager[5] = 2.0f;
  const ZeroedArray<float> copy(eager);
  EXPECT_EQ(copy.paging(), Paging::kAtAllocation);
  EXPECT_EQ(copy[5], 2.0f);
  eager.Reset(2 * kLargeFloats);
  EXPECT_EQ(eager.paging(), Paging::kAtAllocation);
  EXPECT_EQ(ResidentFraction(eager.data(), 2 * kLargeFloats * sizeof(float)), 1.0);
  EXPECT_EQ(eager[5], 0.0f);
}

template <class T>
class PrefaultedGridTest : public ::testing::Test {};
using Lattices = ::testing::Types<HexLattice, SquareLattice>;
TYPED_TEST_SUITE(PrefaultedGridTest, Lattices);

// A prefaulted grid is the same map as a lazy one, scan for scan and across a growth, and its
// storage is resident before anything is written.
TYPED_TEST(PrefaultedGridTest, HoldsTheSameCellsWithItsStorageResident) {
  if (!KernelPopulates()) GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE (Linux < 5.14)";
  const OccupancyModel model = OccupancyModel::FromFactors(0.4, 0.9, 50.0);
  const Eigen::AlignedBox2d box(Eigen::Vector2d(-30.0, -30.0), Eigen::Vector2d(30.0, 30.0));
  GridGrowthPolicy eager_growth;
  eager_growth.prefault = true;
  GridMap<TypeParam> lazy(TypeParam(0.1), model, GridGrowthPolicy(), box);
  GridMap<TypeParam> eager(TypeParam(0.1), model, eager_growth, box);
  const auto bytes = [](const GridMap<TypeParam>& g) { return g.rect().size() * sizeof(float); };
  ASSERT_GE(bytes(eager), std::size_t{1} << 20);  // mapped storage
  EXPECT_EQ(ResidentFraction(eager.centred_probabilities(), bytes(eager)), 1.0);
  EXPECT_LT(ResidentFraction(lazy.centred_probabilities(), bytes(lazy)), 0.5);

  const std::vector<std::vector<Eigen::Vector2d>> scans = {
      {{3.0, 1.0}, {-2.0, 4.5}, {0.5, -6.0}}, {{3.1, 1.1}, {-2.0, 4.4}}, {{10.0, 70.0}}};
  for (const auto& scan : scans) {
    lazy.InsertScan({0.2, -0.1}, scan);
    eager.InsertScan({0.2, -0.1}, scan);
  }
  ASSERT_GE(eager.growth_count(), 1);  // the last scan lies beyond the first storage
  EXPECT_EQ(ResidentFraction(eager.centred_probabilities(), bytes(eager)), 1.0);
  ASSERT_EQ(eager.rect().size(), lazy.rect().size());
  EXPECT_EQ(eager.log_odds_grid().values(), lazy.log_odds_grid().values());
  for (std::size_t i = 0; i < eager.rect().size(); ++i) {
    ASSERT_EQ(eager.centred_probabilities()[i], lazy.centred_probabilities()[i]) << i;
  }
}

}  // namespace
}  // namespace hex_slam
