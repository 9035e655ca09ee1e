#include "hex_slam/common/thread_priority.h"

#include <algorithm>

#ifdef __linux__
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
  errno = 0;
  const int inherited = getpriority(PRIO_PROCESS, thread);
  if (errno != 0) return false;
  return setpriority(PRIO_PROCESS, thread, std::min(kWeakestNiceness, inherited + increment)) == 0;
#else
  (void)increment;
  return false;
#endif
}

}  // namespace hex_slam
