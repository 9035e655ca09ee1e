#include "hex_slam/common/heap_retention.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace hex_slam {

bool RetainFreedMemory() {
#if defined(__GLIBC__)
  // Setting either fixes both: glibc's own adjustment of the thresholds stops.
  return mallopt(M_TRIM_THRESHOLD, static_cast<int>(kRetainedFreeBytes)) == 1 &&
         mallopt(M_MMAP_THRESHOLD, static_cast<int>(kSmallestOwnMapping)) == 1;
#else
  return false;
#endif
}

}  // namespace hex_slam
