// SIGINT, SIGTERM, SIGHUP or a closed stdout (SIGPIPE: `pronk run ... | head`)
// during a command that writes results (run, render, eval, check, train): the
// handler only sets a flag; the command hands out no more work, finishes or
// ends what runs, writes what finished, and exits 128 + the signal.
#pragma once

#include <atomic>

namespace pronk::cli {

// While one lives, those signals set its flag instead of killing the process
// (further writes to a closed stdout fail quietly); the default handlers come
// back when it ends. One at a time.
class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  // True once a signal came; what the rollout pool and the trainer poll.
  const std::atomic<bool>* flag() const;
  bool stopped() const { return flag()->load(); }
  int signal() const;  // the signal received, 0 = none
};

}  // namespace pronk::cli
