#include "tools/msbench/interrupt.h"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace msb {

namespace {
volatile std::sig_atomic_t g_signal = 0;
extern "C" void onSignal(int sig) { g_signal = sig; }
}  // namespace

namespace {
const char* describe(int signal) {
  switch (signal) {
    case SIGTERM:
      return "terminated (SIGTERM)";
    case SIGHUP:
      return "hung up (SIGHUP)";
    case SIGQUIT:
      return "quit (SIGQUIT)";
    default:
      return "interrupted (SIGINT)";
  }
}
}  // namespace

Interrupted::Interrupted(int signal) : std::runtime_error(describe(signal)), signal_(signal) {}

void installInterruptHandlers() {
  struct sigaction sa = {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaction(sig, &sa, nullptr);
  // A closed stdout (`msbench run ... | head -1`) must not kill a run half-way and leave its
  // staging directory: writes to it fail instead, and the run finishes its files.
  std::signal(SIGPIPE, SIG_IGN);
  // A file past the size limit (ulimit -f) fails its write (EFBIG), which writeFileAtomic names,
  // instead of killing msbench with a temporary left behind.
  std::signal(SIGXFSZ, SIG_IGN);
}

bool interruptRequested() { return g_signal != 0; }

namespace {
// Fault injection for the tests of every command's stop (docs/robustness.md, "Interrupts"):
// MSBENCH_TEST_SIGNAL=NAME:N raises signal NAME (INT, TERM, HUP, QUIT) to the process itself at
// the N-th safe point, so a command that finishes in a second is stopped where it would be by a
// real signal, through the same handler. Unset (always, outside the tests): no effect.
struct Injection {
  int signal = 0;
  long at = 0;
};
Injection injectionFromEnvironment() {
  const char* v = std::getenv("MSBENCH_TEST_SIGNAL");
  if (!v) return {};
  const std::string text = v;
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return {};
  const std::string name = text.substr(0, colon);
  const long at = std::strtol(text.c_str() + colon + 1, nullptr, 10);
  const int sig = name == "INT"    ? SIGINT
                  : name == "TERM" ? SIGTERM
                  : name == "HUP"  ? SIGHUP
                  : name == "QUIT" ? SIGQUIT
                                   : 0;
  return sig && at > 0 ? Injection{sig, at} : Injection{};
}
}  // namespace

void throwIfInterrupted() {
  static const Injection injection = injectionFromEnvironment();
  static long safe_points = 0;
  if (injection.signal && ++safe_points == injection.at) std::raise(injection.signal);
  if (g_signal) throw Interrupted(int(g_signal));
}

ExitOnInterrupt::ExitOnInterrupt(std::vector<std::filesystem::path> scratch, std::string who,
                                 std::vector<std::filesystem::path> empty_dirs)
    : watcher_([this, scratch = std::move(scratch), who = std::move(who), empty_dirs = std::move(empty_dirs)] {
        while (!done_.load()) {
          if (g_signal) {
            const int sig = int(g_signal);
            std::error_code ec;
            for (const auto& p : scratch) std::filesystem::remove_all(p, ec);
            for (const auto& p : empty_dirs) std::filesystem::remove(p, ec);  // only if empty
            std::fprintf(stderr, "msbench %s: %s; stopped, nothing written\n", who.c_str(), describe(sig));
            std::fflush(stderr);
            ::_exit(128 + sig);
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
      }) {}

ExitOnInterrupt::~ExitOnInterrupt() {
  done_.store(true);
  watcher_.join();
}

}  // namespace msb
