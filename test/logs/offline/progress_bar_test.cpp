#include "hex_slam/logs/offline/progress_bar.h"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

namespace hex_slam {
namespace logs {
namespace {

// Captures what a progress bar writes.
class Capture {
 public:
  Capture() : file_(std::tmpfile()) {}
  ~Capture() { std::fclose(file_); }
  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    std::rewind(file_);
    std::string s;
    int c;
    while ((c = std::fgetc(file_)) != EOF) s += static_cast<char>(c);
    return s;
  }

 private:
  std::FILE* file_;
};

int Count(const std::string& s, char c) { return static_cast<int>(std::count(s.begin(), s.end(), c)); }

TEST(ProgressBarTest, IntoAFileItWritesAtMostTenPlainLines) {
  Capture out;
  ProgressBarOptions options;  // not interactive
  ProgressBar bar(out.file(), 5000, "run", options);
  for (long i = 1; i <= 5000; ++i) bar.Update(i, i * 1e-4);
  bar.Finish(0.5);
  const std::string text = out.text();
  EXPECT_EQ(Count(text, '\r'), 0);
  EXPECT_EQ(Count(text, '\n'), 10);  // 10%..90%, then the final line
  EXPECT_NE(text.find("100% 5000/5000"), std::string::npos);
}

TEST(ProgressBarTest, OnATerminalRedrawsAreThrottled) {
  Capture out;
  ProgressBarOptions options;
  options.interactive = true;
  options.redraw_interval = 0.1;
  ProgressBar bar(out.file(), 1000, "run", options);
  for (long i = 1; i <= 1000; ++i) bar.Update(i, i * 1e-3);  // one second in all
  bar.Finish(1.0);
  const std::string text = out.text();
  EXPECT_GE(Count(text, '\r'), 9);
  EXPECT_LE(Count(text, '\r'), 12);
  EXPECT_EQ(Count(text, '\n'), 1);
  EXPECT_NE(text.find("100.0%"), std::string::npos);
}

TEST(ProgressBarTest, FinishIsIdempotentAndAZeroTotalIsSafe) {
  Capture out;
  ProgressBar bar(out.file(), 0, "empty", ProgressBarOptions());
  bar.Update(0, 0.0);
  bar.Finish(0.0);
  bar.Finish(0.0);
  bar.Update(5, 1.0);
  EXPECT_EQ(Count(out.text(), '\n'), 1);
}

}  // namespace
}  // namespace logs
}  // namespace hex_slam
