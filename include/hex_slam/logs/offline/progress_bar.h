// A progress bar for long offline runs. On a terminal it redraws one line in place, at most
// `redraw_interval` apart; into a file or pipe (a CI log) it writes a plain line at every tenth
// of the way instead, so logs stay short.
#ifndef HEX_SLAM_LOGS_OFFLINE_PROGRESS_BAR_H_
#define HEX_SLAM_LOGS_OFFLINE_PROGRESS_BAR_H_

#include <chrono>
#include <cstdio>
#include <string>

namespace hex_slam {
namespace logs {

struct ProgressBarOptions {
  bool interactive = false;      // a terminal: redraw in place
  double redraw_interval = 0.1;  // s between redraws on a terminal
  int width = 40;                // characters of bar
  int plain_steps = 10;          // lines per run when not interactive
};

class ProgressBar {
 public:
  // `stream` is not owned; `total` items of work, `label` printed before the bar.
  ProgressBar(std::FILE* stream, long total, const std::string& label,
              const ProgressBarOptions& options);

  // `done` items finished; `elapsed` seconds since the start (for the rate and the estimate).
  void Update(long done, double elapsed);
  // Draws the final state and ends the line.
  void Finish(double elapsed);

  // interactive = whether `stream` is a terminal.
  static ProgressBarOptions ForStream(std::FILE* stream);

 private:
  void Draw(long done, double elapsed, bool final_line);

  std::FILE* stream_;
  long total_;
  std::string label_;
  ProgressBarOptions options_;
  double last_draw_ = -1.0;
  int plain_step_ = 0;
  bool finished_ = false;
};

}  // namespace logs
}  // namespace hex_slam

#endif  // HEX_SLAM_LOGS_OFFLINE_PROGRESS_BAR_H_
