// Background threads (the loop-closure worker, the node's map thread) step back from the scan
// path: when the cores are busy, scans go first. Linux only; elsewhere a no-op.
#ifndef HEX_SLAM_COMMON_THREAD_PRIORITY_H_
#define HEX_SLAM_COMMON_THREAD_PRIORITY_H_

#include <chrono>

namespace hex_slam {

// The weakest nice value a thread can have.
constexpr int kWeakestNiceness = 19;

// How often a background thread looks for the work the scan path hands it quietly, without
// waking it. Waking a sleeping thread is a system call that now and then held the scan path for
// 3 ms (the Intel subset played at 10x on a 2-core VM: 1 % of hand-offs to the loop-closure
// worker, and those fell on the scans that go into the map, the scan path's slowest); a thread
// that polls costs the scan path nothing, and work waits at most this long for it.
constexpr std::chrono::milliseconds kBackgroundPollPeriod{20};

// Raises the calling thread's nice value by `increment` above the one it started with (its
// creator's), up to kWeakestNiceness: relative, so that under `nice -n 19` an absolute value
// would not put the thread above the scan path. Also makes it a batch thread (Linux
// SCHED_BATCH), which never preempts another when it wakes. Returns false when the system
// refused the nice value.
bool LowerThisThreadPriority(int increment);

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_THREAD_PRIORITY_H_
