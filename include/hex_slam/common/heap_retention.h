// What the scan path frees stays in the process for its next scan. Its searches build grids of a
// few hundred kilobytes each time (the correlative search's bounds); glibc gives a thread's freed
// memory back to the system as soon as a little of it lies free, and the next scan faults it in
// again page by page, each fault a trap into the kernel (on a virtual machine, into the
// hypervisor). In the node on the Intel bag with hector's settings at 4x, that made the scans
// that search take 5-10 times their offline time: scans whose matching took over 3 ms, 941 of
// 5498 -> 53; in-node p99 11.7 -> 5.5 ms; peak RSS unchanged (82 / 81 MB).
#ifndef HEX_SLAM_COMMON_HEAP_RETENTION_H_
#define HEX_SLAM_COMMON_HEAP_RETENTION_H_

#include <cstddef>

namespace hex_slam {

// Free memory a heap may keep for reuse instead of returning it: more than a scan's searches
// take, a bound on what retention adds to the peak.
constexpr std::size_t kRetainedFreeBytes = std::size_t{64} << 20;
// Allocations from this size on (a map level's grids) are mapped on their own and returned
// whole when freed, as before: retention never holds a map's old storage.
constexpr std::size_t kSmallestOwnMapping = std::size_t{4} << 20;

// Sets the process's allocator (glibc) to the two limits above; call once, before the threads
// start. Returns false where the allocator is not glibc's or refused (nothing changes then).
bool RetainFreedMemory();

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_HEAP_RETENTION_H_
