#include "ros_input/scan_queue.h"

#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace hex_slam {
namespace node {
namespace {

TEST(ScanQueueTest, KeepsOrderAndDropsTheOldestWhenFullCountingEach) {
  ScanQueue<int> queue(3);
  int dropped = 0;
  for (int i = 0; i < 5; ++i) {
    bool oldest = false;
    ASSERT_TRUE(queue.Push(i, &oldest));
    dropped += oldest;
  }
  EXPECT_EQ(dropped, 2);  // 0 and 1 made room
  EXPECT_EQ(queue.size(), 3u);
  for (int expected : {2, 3, 4}) EXPECT_EQ(queue.Pop()->item, expected);
}

TEST(ScanQueueTest, EveryPushIsEitherPoppedOrCountedAcrossThreads) {
  ScanQueue<int> queue(2);
  constexpr int kItems = 20000;
  std::vector<int> popped;
  std::thread consumer([&] {
    while (auto entry = queue.Pop()) {
      popped.push_back(entry->item);
      if (entry->item == kItems - 1) break;
    }
  });
  int dropped = 0;
  for (int i = 0; i < kItems; ++i) {
    bool oldest = false;
    queue.Push(i, &oldest);
    dropped += oldest;
  }
  consumer.join();
  EXPECT_EQ(static_cast<int>(popped.size()) + dropped, kItems);
  for (std::size_t i = 1; i < popped.size(); ++i) ASSERT_LT(popped[i - 1], popped[i]);
}

TEST(ScanQueueTest, CloseWakesAWaitingConsumerAndRefusesMore) {
  ScanQueue<int> queue(1);
  std::thread consumer([&] { EXPECT_FALSE(queue.Pop().has_value()); });
  queue.Close();
  consumer.join();
  bool oldest = false;
  EXPECT_FALSE(queue.Push(1, &oldest));
}

}  // namespace
}  // namespace node
}  // namespace hex_slam
