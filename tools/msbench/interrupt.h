// SIGINT, SIGTERM, SIGHUP or SIGQUIT during a command: the handler only records the signal; the
// command calls throwIfInterrupted() at its safe points (between ticks, frames, views, report
// stages), so it stops there and the exception unwinds through the output objects, which remove
// their temporary files (no DIR.partial, no LOG.tmp). main() prints one line and exits 128 +
// signal (130, 143, 129, 131).
#pragma once

#include <stdexcept>
#include <string>

namespace msb {

/// Thrown at a safe point after SIGINT, SIGTERM, SIGHUP or SIGQUIT.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  /// The signal received.
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// Installs the SIGINT, SIGTERM, SIGHUP and SIGQUIT handlers and ignores SIGPIPE (once, at start-up).
void installInterruptHandlers();
/// Throws Interrupted if a signal arrived.
void throwIfInterrupted();
/// True if a signal arrived (for loops that stop on their own terms, e.g. the sweep runner).
bool interruptRequested();

}  // namespace msb
