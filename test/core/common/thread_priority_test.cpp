// The kernel is the oracle: what a thread's policy and nice value read back as after it stepped
// back, and that the thread that started it keeps its own.
#include "hex_slam/common/thread_priority.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#ifdef __linux__
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace hex_slam {
namespace {

#ifdef __linux__
struct ThreadScheduling {
  int policy = -1;
  int nice = 0;
};

ThreadScheduling ThisThreadsScheduling() {
  const pid_t thread = static_cast<pid_t>(syscall(SYS_gettid));
  return {sched_getscheduler(thread), getpriority(PRIO_PROCESS, static_cast<id_t>(thread))};
}

TEST(ThreadPriorityTest, ALoweredThreadIsABatchThreadNicerByTheIncrementAndItsCreatorIsNot) {
  const ThreadScheduling creator = ThisThreadsScheduling();
  ThreadScheduling lowered;
  bool accepted = false;
  std::thread([&] {
    accepted = LowerThisThreadPriority(5);
    lowered = ThisThreadsScheduling();
  }).join();
  ASSERT_TRUE(accepted);
  EXPECT_EQ(lowered.policy, SCHED_BATCH);
  EXPECT_EQ(lowered.nice, std::min(kWeakestNiceness, creator.nice + 5));
  EXPECT_EQ(ThisThreadsScheduling().policy, creator.policy);
  EXPECT_EQ(ThisThreadsScheduling().nice, creator.nice);
}

TEST(ThreadPriorityTest, ALoweredThreadAsksForTheShortestSliceAndItsCreatorKeepsItsOwn) {
  const std::chrono::nanoseconds creator = ThisThreadsSlice();
  if (creator.count() == 0) {
    GTEST_SKIP() << "this kernel reports no per-thread time slice (Linux before 6.12)";
  }
  std::chrono::nanoseconds lowered{};
  bool accepted = false;
  std::thread([&] {
    accepted = LowerThisThreadPriority(5);
    lowered = ThisThreadsSlice();
  }).join();
  ASSERT_TRUE(accepted);
  EXPECT_EQ(lowered, std::chrono::nanoseconds(kBackgroundSlice));
  EXPECT_LT(lowered, creator);
  EXPECT_EQ(ThisThreadsSlice(), creator);
}

TEST(ThreadPriorityTest, AnIdleThreadIsInTheIdleClassAndItsCreatorIsNot) {
  const ThreadScheduling creator = ThisThreadsScheduling();
  ThreadScheduling idle;
  bool accepted = false;
  std::thread([&] {
    accepted = MakeThisThreadIdle();
    idle = ThisThreadsScheduling();
  }).join();
  ASSERT_TRUE(accepted);
  EXPECT_EQ(idle.policy, SCHED_IDLE);
  EXPECT_EQ(ThisThreadsScheduling().policy, creator.policy);
  EXPECT_NE(creator.policy, SCHED_IDLE);
}
#else
TEST(ThreadPriorityTest, ALoweredThreadIsABatchThreadNicerByTheIncrementAndItsCreatorIsNot) {
  GTEST_SKIP() << "not Linux: thread priorities are left alone";
}
#endif

}  // namespace
}  // namespace hex_slam
