#include "stop_signal.h"

#include <csignal>

namespace pronk::cli {
namespace {

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
std::atomic<int> g_signal{0};
std::atomic<bool> g_stop{false};
extern "C" void onStopSignal(int signal) {
  if (g_signal == 0) g_signal = signal;  // the first one says why; lock-free atomics: safe in a handler
  g_stop = true;
}

}  // namespace

StopOnSignal::StopOnSignal() {
  g_signal = 0;
  g_stop = false;
  for (int s : kStopSignals) std::signal(s, onStopSignal);
}

StopOnSignal::~StopOnSignal() {
  for (int s : kStopSignals) std::signal(s, SIG_DFL);
}

const std::atomic<bool>* StopOnSignal::flag() const { return &g_stop; }
int StopOnSignal::signal() const { return g_signal; }

}  // namespace pronk::cli
