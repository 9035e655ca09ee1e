// The scans waiting for the SLAM thread. ROS's own subscriber queue drops the oldest message
// when full and tells nobody; this one does the same with a count, so every scan the node could
// not keep up with shows on /diagnostics and in the log. Its receiving side only appends, so the
// subscriber thread is never busy long enough for ROS to drop anything before it.
#ifndef HEX_SLAM_NODE_ROS_INPUT_SCAN_QUEUE_H_
#define HEX_SLAM_NODE_ROS_INPUT_SCAN_QUEUE_H_

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace hex_slam {
namespace node {

template <class T>
class ScanQueue {
 public:
  using Clock = std::chrono::steady_clock;
  struct Entry {
    T item;
    Clock::time_point received;  // when the subscriber got it, for the latency figures
  };

  // `capacity` >= 1 (hector_mapping's scan_subscriber_queue_size).
  explicit ScanQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  // Appends; when full, the oldest entry makes room. Returns whether one did. False after Close.
  bool Push(T item, bool* dropped_oldest) {
    *dropped_oldest = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (closed_) return false;
      if (entries_.size() >= capacity_) {
        entries_.pop_front();
        *dropped_oldest = true;
      }
      entries_.push_back({std::move(item), Clock::now()});
    }
    ready_.notify_one();
    return true;
  }

  // The oldest entry; waits for one. Nothing once closed (entries still queued are discarded).
  std::optional<Entry> Pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return closed_ || !entries_.empty(); });
    if (closed_) return std::nullopt;
    Entry entry = std::move(entries_.front());
    entries_.pop_front();
    return entry;
  }

  // Wakes Pop for good.
  void Close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
      entries_.clear();
    }
    ready_.notify_all();
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_.size();
  }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Entry> entries_;
  bool closed_ = false;
};

}  // namespace node
}  // namespace hex_slam

#endif  // HEX_SLAM_NODE_ROS_INPUT_SCAN_QUEUE_H_
