// SIGINT / SIGTERM during a long command: the handler only records the signal; the command's
// loop calls throwIfInterrupted() between ticks, so the run stops at the end of the current
// tick and the exception unwinds through the output objects, which remove their temporary files
// (no DIR.partial, no LOG.tmp). main() prints one line and exits 128 + signal (130, 143).
#pragma once

#include <stdexcept>
#include <string>

namespace msb {

/// Thrown between ticks after SIGINT or SIGTERM.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  /// The signal received.
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// Installs the SIGINT and SIGTERM handlers (once, at start-up).
void installInterruptHandlers();
/// Throws Interrupted if a signal arrived.
void throwIfInterrupted();
/// True if a signal arrived (for loops that stop on their own terms, e.g. the sweep runner).
bool interruptRequested();

}  // namespace msb
