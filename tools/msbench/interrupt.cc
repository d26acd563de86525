#include "tools/msbench/interrupt.h"

#include <csignal>

namespace msb {

namespace {
volatile std::sig_atomic_t g_signal = 0;
extern "C" void onSignal(int sig) { g_signal = sig; }
}  // namespace

Interrupted::Interrupted(int signal)
    : std::runtime_error(signal == SIGTERM ? "terminated (SIGTERM)" : "interrupted (SIGINT)"), signal_(signal) {}

void installInterruptHandlers() {
  struct sigaction sa = {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool interruptRequested() { return g_signal != 0; }

void throwIfInterrupted() {
  if (g_signal) throw Interrupted(int(g_signal));
}

}  // namespace msb
