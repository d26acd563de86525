#include "tools/msbench/interrupt.h"

#include <csignal>

namespace msb {

namespace {
volatile std::sig_atomic_t g_signal = 0;
extern "C" void onSignal(int sig) { g_signal = sig; }
}  // namespace

namespace {
const char* describe(int signal) {
  switch (signal) {
    case SIGTERM: return "terminated (SIGTERM)";
    case SIGHUP: return "hung up (SIGHUP)";
    case SIGQUIT: return "quit (SIGQUIT)";
    default: return "interrupted (SIGINT)";
  }
}
}  // namespace

Interrupted::Interrupted(int signal) : std::runtime_error(describe(signal)), signal_(signal) {}

void installInterruptHandlers() {
  struct sigaction sa = {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaction(sig, &sa, nullptr);
}

bool interruptRequested() { return g_signal != 0; }

void throwIfInterrupted() {
  if (g_signal) throw Interrupted(int(g_signal));
}

}  // namespace msb
