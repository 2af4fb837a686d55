#include "stop_signal.h"

#include <csignal>

namespace pronk::cli {
namespace {

std::atomic<int> g_signal{0};
std::atomic<bool> g_stop{false};
extern "C" void onStopSignal(int signal) {
  g_signal = signal;  // lock-free atomics: safe in a handler
  g_stop = true;
}

}  // namespace

StopOnSignal::StopOnSignal() {
  g_signal = 0;
  g_stop = false;
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
}

StopOnSignal::~StopOnSignal() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

const std::atomic<bool>* StopOnSignal::flag() const { return &g_stop; }
int StopOnSignal::signal() const { return g_signal; }

}  // namespace pronk::cli
