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

// The time slice a background thread asks for: the shortest the kernel grants (0.1 ms). A thread
// just given a core keeps it against a waking scan until it has run its slice (the kernel's
// default here, 1.4 ms on 2 cores, was where the scan path's p99 went with loop closure on); a
// short one nearly always has, so the scan takes the core at once. It takes no share away from
// the thread, which is still switched only when another wants the core.
constexpr std::chrono::microseconds kBackgroundSlice{100};

// Raises the calling thread's nice value by `increment` above the one it started with (its
// creator's), up to kWeakestNiceness: relative, so that under `nice -n 19` an absolute value
// would not put the thread above the scan path. Also makes it a batch thread (Linux
// SCHED_BATCH), which never preempts another when it wakes, with kBackgroundSlice as its time
// slice where the kernel has per-thread slices (Linux 6.12 on). Returns false when the system
// refused the nice value.
bool LowerThisThreadPriority(int increment);

// The calling thread's time slice as the kernel reports it; zero where it reports none (not
// Linux, or Linux before 6.12).
std::chrono::nanoseconds ThisThreadsSlice();

// Puts the calling thread in Linux's idle class (SCHED_IDLE): it runs on what every other
// thread leaves. Unlike a nice value, a thread woken on its core takes it at once (a batch
// thread at +10 holds it for the rest of its slice, kBackgroundSlice at best), and the
// scheduler counts its core as free when it places a waking thread. The price is starvation:
// beside ordinary processes that keep every core busy it gets about 0.3 % of a core, and a
// thread of ours that waits for it then waits that long. An unprivileged thread cannot leave
// the class again. Returns false when the system refused.
bool MakeThisThreadIdle();

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_THREAD_PRIORITY_H_
