// SIGINT / SIGTERM during a long command (run, eval, train): the handler only
// sets a flag; the command hands out no more work, finishes what runs, writes
// what finished, and exits 128 + the signal.
#pragma once

#include <atomic>

namespace pronk::cli {

// While one lives, SIGINT and SIGTERM set its flag instead of killing the
// process; the default handlers come back when it ends. One at a time.
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
