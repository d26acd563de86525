// A run that dies of a fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) explains itself:
// the handler writes one line with the signal, the command and the last completed tick and its
// simulated time, then a backtrace (glibc backtrace_symbols_fd), to standard error — the run's
// log in a sweep — and lets the signal end the process as before (exit status = the signal, a
// core file where enabled). Everything the handler does is async-signal-safe: fixed buffers,
// write(2), no allocation.
#pragma once

#include <cstdint>

namespace msb {

/// Installs the fatal-signal handlers (once, at start-up; runs on its own stack, so a stack
/// overflow is reported too). `command` names the running command in the report line.
void installCrashHandler(const char* command);

/// Records the progress of the current run (called after every tick): the report line names it.
void setCrashContext(int64_t tick, double sim_time_s);

/// Writes the report for `signal` to `fd` exactly as the handler does (for tests).
void writeCrashReport(int fd, int signal);

}  // namespace msb
