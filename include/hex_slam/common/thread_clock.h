// The calling thread's own CPU time: how long a piece of work held a core, apart from the time
// other threads held it (a busy machine, or a background thread beside it on too few cores).
#ifndef HEX_SLAM_COMMON_THREAD_CLOCK_H_
#define HEX_SLAM_COMMON_THREAD_CLOCK_H_

namespace hex_slam {

// The calling thread's CPU time so far (s); 0 where the system cannot tell.
double ThreadCpuSeconds();

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_THREAD_CLOCK_H_
