#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace pronk::cli {
namespace {

constexpr double kQuietStart = 3.0;   // s before the first line
constexpr double kTtyPeriod = 0.25;   // s between updates on a terminal
constexpr double kLogPeriod = 10.0;   // s between lines in a log

std::string clock(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char text[32];
  if (s >= 3600) std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

Progress::Progress(std::string what, size_t total)
    : what_(std::move(what)), total_(total), tty_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() {
  if (shown_ && tty_) std::fputc('\n', stderr);
}

void Progress::done(size_t finished) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (elapsed < kQuietStart || (since < (tty_ ? kTtyPeriod : kLogPeriod) && finished < total_)) return;
  last_ = now;
  shown_ = true;
  const double rate = finished / elapsed;
  const std::string eta = rate > 0 ? clock((total_ - finished) / rate) : "-";
  std::fprintf(stderr, "%s%s %zu/%zu, %.2f %ss/s, ETA %s%s", tty_ ? "\r" : "", what_.c_str(), finished, total_, rate,
               what_.c_str(), eta.c_str(), tty_ ? "\033[K" : "\n");
  std::fflush(stderr);
}

}  // namespace pronk::cli
