#include "hex_slam/logs/offline/progress_bar.h"

#include <unistd.h>

#include <algorithm>

namespace hex_slam {
namespace logs {

ProgressBar::ProgressBar(std::FILE* stream, long total, const std::string& label,
                         const ProgressBarOptions& options)
    : stream_(stream), total_(std::max(total, 1L)), label_(label), options_(options) {}

ProgressBarOptions ProgressBar::ForStream(std::FILE* stream) {
  ProgressBarOptions options;
  options.interactive = ::isatty(::fileno(stream)) == 1;
  return options;
}

void ProgressBar::Update(long done, double elapsed) {
  if (finished_) return;
  if (options_.interactive) {
    if (last_draw_ >= 0.0 && elapsed - last_draw_ < options_.redraw_interval) return;
    last_draw_ = elapsed;
    Draw(done, elapsed, false);
    return;
  }
  const int step = static_cast<int>(options_.plain_steps * std::min(done, total_) / total_);
  if (step > plain_step_ && step < options_.plain_steps) {
    plain_step_ = step;
    Draw(done, elapsed, false);
  }
}

void ProgressBar::Finish(double elapsed) {
  if (finished_) return;
  Draw(total_, elapsed, true);
  finished_ = true;
}

void ProgressBar::Draw(long done, double elapsed, bool final_line) {
  done = std::clamp(done, 0L, total_);
  const double fraction = static_cast<double>(done) / total_;
  const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
  const double remaining = rate > 0.0 ? (total_ - done) / rate : 0.0;
  if (options_.interactive) {
    const int filled = static_cast<int>(fraction * options_.width);
    const std::string bar = std::string(filled, '#') + std::string(options_.width - filled, '.');
    std::fprintf(stream_, "\r%s [%s] %5.1f%% %ld/%ld %.0f/s %.0f s left ", label_.c_str(),
                 bar.c_str(), 100.0 * fraction, done, total_, rate, remaining);
    if (final_line) std::fputc('\n', stream_);
  } else {
    std::fprintf(stream_, "%s %3.0f%% %ld/%ld %.0f/s %.1f s\n", label_.c_str(), 100.0 * fraction,
                 done, total_, rate, elapsed);
  }
  std::fflush(stream_);
}

}  // namespace logs
}  // namespace hex_slam
