// Inserts scans into a submap on a thread of its own, in the order they were pushed: the newer of
// the two active submaps is only matched against once the older is finished, so its insertions
// need not be on the scan path. The scan path pushes (a copy of the points, under a lock held
// only for the push, without waking the thread: it looks every kBackgroundPollPeriod) and calls
// WaitIdle before it reads the submap; nothing else touches it meanwhile. WaitIdle inserts what
// the thread has not started itself: with more busy threads than cores the filler thread often
// waits for a core with a dozen scans queued, and the scan path would otherwise sleep until it
// got one.
//
// The thread runs below the scan path (kSubmapFillerNiceness): whatever it has not done by then,
// the scan path does at the wait, so yielding to it costs nothing but a longer wait once per
// submap, while at equal priority it preempts the scan path on a machine with fewer free cores
// than busy threads (hex_slam_offline: scan path, filler and worker on 2 cores).
#ifndef HEX_SLAM_MAPPING_SUBMAP_FILLER_H_
#define HEX_SLAM_MAPPING_SUBMAP_FILLER_H_

#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "hex_slam/common/thread_priority.h"
#include "hex_slam/mapping/submap.h"

namespace hex_slam {
namespace mapping {

// The filler thread's nice increment over its creator's. Intel subset offline (loop closure on,
// the worker at 0), five runs each: scan path p99 1.42-1.60 ms at 0, 0.58-0.89 ms at 10; mean
// per scan and trajectory unchanged.
constexpr int kSubmapFillerNiceness = 10;

template <class Lattice>
class SubmapFiller {
 public:
  SubmapFiller() : thread_(&SubmapFiller::Run, this) {}
  ~SubmapFiller() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  SubmapFiller(const SubmapFiller&) = delete;
  SubmapFiller& operator=(const SubmapFiller&) = delete;

  // Queues the scan (`origin`, `points` in the submap's local frame) for `submap`, and after
  // it the growth of its storage for `scans_to_come` more scans (Submap::CoverAhead; 0: none).
  void Push(std::shared_ptr<Submap<Lattice>> submap, const Eigen::Vector2d& origin,
            const std::vector<Eigen::Vector2d>& points, int scans_to_come) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back({std::move(submap), origin, points, scans_to_come});
    }
  }

  // Returns once the thread itself has inserted every scan pushed so far (look-ahead included),
  // without helping it: for tests of what the thread does when it keeps up.
  void WaitForThread() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
  }

  // Returns once every scan pushed so far is in its submap, inserting those the thread has not
  // started on the caller's thread (in their order); rethrows what an insertion threw.
  void WaitIdle() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return !busy_; });
    if (!queue_.empty()) {
      std::deque<Item> queued;
      queued.swap(queue_);
      busy_ = true;  // the thread leaves the queue alone until these are in
      lock.unlock();
      std::exception_ptr error = InsertAll(&queued, /*cover_ahead=*/false);
      lock.lock();
      busy_ = false;
      if (error && !error_) error_ = error;
    }
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  struct Item {
    std::shared_ptr<Submap<Lattice>> submap;
    Eigen::Vector2d origin;
    std::vector<Eigen::Vector2d> points;
    int scans_to_come;
  };

  // Inserts `items` in order; returns the first error (the items after it are still inserted:
  // each scan is independent of the others). The look-ahead growths only with `cover_ahead`
  // (the filler's own thread): done on the scan path, at WaitIdle, a look-ahead is the very
  // growth copy on the scan path it exists to avoid.
  static std::exception_ptr InsertAll(std::deque<Item>* items, bool cover_ahead) {
    std::exception_ptr first;
    for (Item& item : *items) {
      try {
        item.submap->InsertScan(item.origin, item.points);
        if (cover_ahead && item.scans_to_come > 0) item.submap->CoverAhead(item.scans_to_come);
      } catch (...) {
        if (!first) first = std::current_exception();
      }
    }
    return first;
  }

  void Run() {
    LowerThisThreadPriority(kSubmapFillerNiceness);
    for (;;) {
      std::deque<Item> next;  // one item, for InsertAll
      bool cover_ahead;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        const auto work = [this] { return stop_ || (!queue_.empty() && !busy_); };
        while (!wake_.wait_for(lock, kBackgroundPollPeriod, work)) {
        }
        if (stop_) return;
        next.push_back(std::move(queue_.front()));
        queue_.pop_front();
        busy_ = true;
        // Behind: the next scan's look-ahead, a better guess, will do for both.
        cover_ahead = queue_.empty();
      }
      const std::exception_ptr error = InsertAll(&next, cover_ahead);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        busy_ = false;
        if (error && !error_) error_ = error;
      }
      idle_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::deque<Item> queue_;
  bool busy_ = false;
  bool stop_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: starts once everything above exists
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_SUBMAP_FILLER_H_
