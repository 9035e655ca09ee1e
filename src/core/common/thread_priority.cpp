#include "hex_slam/common/thread_priority.h"

#include <algorithm>
#include <cstdint>

#ifdef __linux__
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace hex_slam {

#ifdef __linux__
namespace {

// The argument of sched_setattr and sched_getattr, as the kernel lays it out (its own header,
// linux/sched/types.h, redefines glibc's sched_param; glibc 2.36 wraps neither call).
struct SchedAttr {
  std::uint32_t size;
  std::uint32_t sched_policy;
  std::uint64_t sched_flags;
  std::int32_t sched_nice;
  std::uint32_t sched_priority;
  std::uint64_t sched_runtime;  // a fair-class thread's slice (Linux 6.12 on)
  std::uint64_t sched_deadline;
  std::uint64_t sched_period;
  std::uint32_t sched_util_min;
  std::uint32_t sched_util_max;
};

// Asks for kBackgroundSlice as the thread's time slice (older kernels ignore the field).
void ShortenThisThreadsSlice(pid_t thread, int nice) {
  SchedAttr attr{};
  attr.size = sizeof(attr);
  attr.sched_policy = SCHED_BATCH;
  attr.sched_nice = nice;
  attr.sched_runtime = static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(kBackgroundSlice).count());
  syscall(SYS_sched_setattr, thread, &attr, 0U);
}

}  // namespace
#endif

bool LowerThisThreadPriority(int increment) {
#ifdef __linux__
  // On Linux the nice value is per thread; a new thread starts at its creator's, read back here.
  const id_t thread = static_cast<id_t>(syscall(SYS_gettid));
  // Batch scheduling keeps the nice value and takes away the right to preempt on wakeup: a
  // background thread woken by its timer (kBackgroundPollPeriod) or a job waits for the next
  // tick or a free core instead of taking the scan path's core there and then. Refused or not,
  // the nice value below still applies.
  const sched_param batch{};
  sched_setscheduler(static_cast<pid_t>(thread), SCHED_BATCH, &batch);
  errno = 0;
  const int inherited = getpriority(PRIO_PROCESS, thread);
  if (errno != 0) return false;
  const int nice = std::min(kWeakestNiceness, inherited + increment);
  if (setpriority(PRIO_PROCESS, thread, nice) != 0) return false;
  ShortenThisThreadsSlice(static_cast<pid_t>(thread), nice);
  return true;
#else
  (void)increment;
  return false;
#endif
}

std::chrono::nanoseconds ThisThreadsSlice() {
#ifdef __linux__
  SchedAttr attr{};
  if (syscall(SYS_sched_getattr, 0, &attr, sizeof(attr), 0U) != 0) return {};
  return std::chrono::nanoseconds(attr.sched_runtime);
#else
  return {};
#endif
}

bool MakeThisThreadIdle() {
#ifdef __linux__
  const sched_param idle{};
  return sched_setscheduler(static_cast<pid_t>(syscall(SYS_gettid)), SCHED_IDLE, &idle) == 0;
#else
  return false;
#endif
}

}  // namespace hex_slam
