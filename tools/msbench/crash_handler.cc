#include "tools/msbench/crash_handler.h"

#include <execinfo.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>

namespace msb {

namespace {

// Progress of the current run, read by the handler (lock-free atomics: safe in a handler).
std::atomic<int64_t> g_tick{-1};
std::atomic<int64_t> g_sim_time_ms{-1};
const char* g_command = "?";

constexpr int kFatalSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

// Appends text / a decimal integer to a fixed buffer (no allocation, no locale).
struct Line {
  char text[512];
  size_t n = 0;
  void add(const char* s) {
    while (*s && n + 1 < sizeof(text)) text[n++] = *s++;
  }
  void add(int64_t v) {
    char digits[24];
    int k = 0;
    const bool negative = v < 0;
    uint64_t u = negative ? uint64_t(0) - uint64_t(v) : uint64_t(v);
    do digits[k++] = char('0' + u % 10);
    while ((u /= 10) && k < 23);
    if (negative) add("-");
    while (k > 0 && n + 1 < sizeof(text)) text[n++] = digits[--k];
  }
};

void writeAll(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w <= 0) return;
    p += w, n -= size_t(w);
  }
}

const char* signalName(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGILL:
      return "SIGILL";
    case SIGABRT:
      return "SIGABRT";
    default:
      return "signal";
  }
}

extern "C" void onFatalSignal(int sig) {
  writeCrashReport(STDERR_FILENO, sig);
  // SA_RESETHAND restored the default action: re-raise so the process ends with this signal
  // (a fault re-executes the faulting instruction on return, which ends it the same way).
  ::raise(sig);
}

}  // namespace

void writeCrashReport(int fd, int sig) {
  Line l;
  l.add("\nmsbench ");
  l.add(g_command);
  l.add(": fatal signal ");
  l.add(int64_t(sig));
  l.add(" (");
  l.add(signalName(sig));
  l.add(")");
  const int64_t tick = g_tick.load(std::memory_order_relaxed);
  if (tick >= 0) {
    const int64_t ms = g_sim_time_ms.load(std::memory_order_relaxed);
    l.add(" after tick ");
    l.add(tick);
    l.add(" (t = ");
    l.add(ms / 1000);
    l.add(".");
    const int64_t frac = ms % 1000;
    if (frac < 100) l.add("0");
    if (frac < 10) l.add("0");
    l.add(frac);
    l.add(" s simulated)");
  } else {
    l.add(" before the first tick");
  }
  l.add("\nbacktrace:\n");
  writeAll(fd, l.text, l.n);
  void* frames[64];
  const int n = ::backtrace(frames, 64);
  ::backtrace_symbols_fd(frames, n, fd);
}

void installCrashHandler(const char* command) {
  g_command = command;
  // backtrace() loads libgcc on its first call (which allocates): do it now, not in the handler.
  void* warm[2];
  ::backtrace(warm, 2);
  // Its own stack, so that a stack overflow can still be reported.
  static char alt_stack[64 * 1024];
  stack_t ss = {};
  ss.ss_sp = alt_stack;
  ss.ss_size = sizeof(alt_stack);
  ::sigaltstack(&ss, nullptr);
  struct sigaction sa = {};
  sa.sa_handler = onFatalSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND | SA_ONSTACK | SA_NODEFER;
  for (const int sig : kFatalSignals) ::sigaction(sig, &sa, nullptr);
}

void setCrashContext(int64_t tick, double sim_time_s) {
  g_sim_time_ms.store(int64_t(sim_time_s * 1000.0 + 0.5), std::memory_order_relaxed);
  g_tick.store(tick, std::memory_order_relaxed);
}

}  // namespace msb
