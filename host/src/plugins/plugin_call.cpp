#include "plugin_call.h"

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

#include "pronk/plugin_registry.h"

namespace pronk {
namespace {

struct CallOnThread {
  const char* plugin = nullptr;
  const char* factory = nullptr;
  const char* call = nullptr;
};
thread_local CallOnThread t_call;

constexpr int kFatalSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
constexpr int kFatalSignalCount = sizeof kFatalSignals / sizeof kFatalSignals[0];
// What handled each before (the default, or a sanitizer's report): it gets the signal next.
struct sigaction g_previous[kFatalSignalCount];

// Only write(2) here: the handler may run anywhere.
void say(const char* text) {
  if (!text) return;
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<size_t>(n);
  }
}

// " in plugin PATH, FACTORY's CALL()" or, without a factory, " in plugin PATH's CALL()".
void sayCall(const CallOnThread& c) {
  say(" in plugin ");
  say(c.plugin);
  if (c.factory) {
    say(", ");
    say(c.factory);
  }
  say("'s ");
  say(c.call);
  say("()\n");
}

extern "C" void onFatalSignal(int signal) {
  const CallOnThread c = t_call;
  if (c.call) {
    char number[4] = {char('0' + signal / 10 % 10), char('0' + signal % 10), 0, 0};
    say("pronk: fatal signal ");
    say(signal >= 10 ? number : number + 1);
    say(" (");
    say(sigdescr_np(signal));
    say(")");
    sayCall(c);
  }
  // Then what handled it before: the default action, or a sanitizer's report.
  for (int i = 0; i < kFatalSignalCount; ++i) {
    if (kFatalSignals[i] == signal) sigaction(signal, &g_previous[i], nullptr);
  }
  std::raise(signal);
}

extern "C" void onExit() {
  const CallOnThread c = t_call;
  if (!c.call) return;
  say("pronk: exit() was called");
  sayCall(c);
}

}  // namespace

PluginCallScope::PluginCallScope(const char* plugin, const char* factory, const char* call)
    : previous_{t_call.plugin, t_call.factory, t_call.call} {
  t_call = {plugin, factory, call};
}

PluginCallScope::~PluginCallScope() { t_call = {previous_[0], previous_[1], previous_[2]}; }

void reportPluginCrashes() {
  static bool installed = false;  // twice would take its own handler for the one before
  if (installed) return;
  installed = true;
  struct sigaction action {};
  action.sa_handler = onFatalSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_NODEFER;
  for (int i = 0; i < kFatalSignalCount; ++i) sigaction(kFatalSignals[i], &action, &g_previous[i]);
  std::atexit(onExit);
}

}  // namespace pronk
