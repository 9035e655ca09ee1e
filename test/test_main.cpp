#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

namespace {

// A test that hangs would hold the whole suite (and CI's time budget) until it is killed, with no
// word of which test it was. The watchdog aborts the binary, naming the test, once one test has run
// for longer than HEX_SLAM_TEST_TIMEOUT seconds: the longest takes about 50 s on a loaded machine.
constexpr int kDefaultTimeoutSeconds = 600;

class Watchdog : public ::testing::EmptyTestEventListener {
 public:
  explicit Watchdog(std::chrono::seconds limit) : limit_(limit), thread_([this] { Watch(); }) {}

  ~Watchdog() override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

  void OnTestStart(const ::testing::TestInfo& info) override {
    std::lock_guard<std::mutex> lock(mutex_);
    test_ = std::string(info.test_suite_name()) + "." + info.name();
    running_ = true;
    ++generation_;
    changed_.notify_all();
  }

  void OnTestEnd(const ::testing::TestInfo&) override {
    std::lock_guard<std::mutex> lock(mutex_);
    running_ = false;
    changed_.notify_all();
  }

 private:
  void Watch() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      if (!running_) {
        changed_.wait(lock);
        continue;
      }
      const long generation = generation_;
      const bool ended = changed_.wait_for(
          lock, limit_, [&] { return done_ || !running_ || generation_ != generation; });
      if (!ended) {
        std::fprintf(stderr, "\nerror: test %s still running after %lld s: aborting (a hang?)\n",
                     test_.c_str(), static_cast<long long>(limit_.count()));
        std::fflush(stderr);
        std::abort();
      }
    }
  }

  const std::chrono::seconds limit_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::string test_;
  bool running_ = false;
  bool done_ = false;
  long generation_ = 0;
  std::thread thread_;
};

std::chrono::seconds TimeoutFromEnvironment() {
  const char* text = std::getenv("HEX_SLAM_TEST_TIMEOUT");
  if (text == nullptr || *text == '\0') return std::chrono::seconds(kDefaultTimeoutSeconds);
  char* end = nullptr;
  const long seconds = std::strtol(text, &end, 10);
  if (*end != '\0' || seconds <= 0) {
    std::fprintf(stderr, "warning: HEX_SLAM_TEST_TIMEOUT=%s is not a positive number of seconds;"
                 " using %d\n", text, kDefaultTimeoutSeconds);
    return std::chrono::seconds(kDefaultTimeoutSeconds);
  }
  return std::chrono::seconds(seconds);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // The listener list owns what is appended but deletes it only at exit: the watchdog is released
  // and deleted here so that its thread has stopped before main returns.
  auto* watchdog = new Watchdog(TimeoutFromEnvironment());
  ::testing::TestEventListeners& listeners = ::testing::UnitTest::GetInstance()->listeners();
  listeners.Append(watchdog);
  const int result = RUN_ALL_TESTS();
  delete listeners.Release(watchdog);
  return result;
}
