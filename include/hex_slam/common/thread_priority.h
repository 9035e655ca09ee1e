// Background threads (the loop-closure worker, the node's map thread) step back from the scan
// path: when the cores are busy, scans go first. Linux only; elsewhere a no-op.
#ifndef HEX_SLAM_COMMON_THREAD_PRIORITY_H_
#define HEX_SLAM_COMMON_THREAD_PRIORITY_H_

namespace hex_slam {

// The weakest nice value a thread can have.
constexpr int kWeakestNiceness = 19;

// Raises the calling thread's nice value by `increment` above the one it started with (its
// creator's), up to kWeakestNiceness: relative, so that under `nice -n 19` an absolute value
// would not put the thread above the scan path. Returns false when the system refused.
bool LowerThisThreadPriority(int increment);

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_THREAD_PRIORITY_H_
