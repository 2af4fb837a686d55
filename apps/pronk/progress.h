// A progress line on stderr for long runs: "jump k/N, x jumps/s, ETA ...".
// On a terminal one line updates in place; in a log, a plain line every few
// seconds. Nothing is printed for a run that ends within the first seconds.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace pronk::cli {

class Progress {
 public:
  Progress(std::string what, size_t total);
  ~Progress();  // ends the terminal's updating line
  void done(size_t finished);

 private:
  std::string what_;
  size_t total_;
  bool tty_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace pronk::cli
