#include "hex_slam/common/thread_priority.h"

#include <algorithm>

#ifdef __linux__
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace hex_slam {

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
  return setpriority(PRIO_PROCESS, thread, std::min(kWeakestNiceness, inherited + increment)) == 0;
#else
  (void)increment;
  return false;
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
