// The allocator's own accounting (glibc's mallinfo2) is the oracle: after RetainFreedMemory a
// search-sized block comes from the heap and stays there once freed, while a map-sized one is
// still mapped on its own.
#include "hex_slam/common/heap_retention.h"

#include <cstdlib>
#include <cstring>

#include <gtest/gtest.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace hex_slam {
namespace {

#if defined(__GLIBC__)
TEST(HeapRetentionTest, ASearchSizedBlockStaysInTheHeapAndAMapSizedOneIsMappedAlone) {
  ASSERT_TRUE(RetainFreedMemory());
  // A bounds grid of the Intel bag's typical search: 600 x 600 pixels of a byte.
  constexpr std::size_t kSearchBlock = 600 * 600;
  const struct mallinfo2 before = mallinfo2();
  void* search = std::malloc(kSearchBlock);
  ASSERT_NE(search, nullptr);
  std::memset(search, 1, kSearchBlock);
  EXPECT_EQ(mallinfo2().hblks, before.hblks);  // not a mapping of its own (the default's 128 kB)
  std::free(search);
  // Freed, it stays in the heap (fordblks: free bytes held), not given back to the system.
  EXPECT_GE(mallinfo2().fordblks, before.fordblks + kSearchBlock);

  void* map = std::malloc(2 * kSmallestOwnMapping);
  ASSERT_NE(map, nullptr);
  EXPECT_EQ(mallinfo2().hblks, before.hblks + 1);
  std::free(map);
  EXPECT_EQ(mallinfo2().hblks, before.hblks);
}
#else
TEST(HeapRetentionTest, ASearchSizedBlockStaysInTheHeapAndAMapSizedOneIsMappedAlone) {
  GTEST_SKIP() << "not glibc: RetainFreedMemory changes nothing";
}
#endif

}  // namespace
}  // namespace hex_slam
