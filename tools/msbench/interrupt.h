// SIGINT, SIGTERM, SIGHUP or SIGQUIT during a command: the handler only records the signal; the
// command calls throwIfInterrupted() at its safe points (between ticks, frames, views, report
// stages), so it stops there and the exception unwinds through the output objects, which remove
// their temporary files (no DIR.partial, no LOG.tmp). main() prints one line and exits 128 +
// signal (130, 143, 129, 131).
#pragma once

#include <atomic>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

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

/// For work inside a library that has no safe points (assimp, mesh cutting) and writes only to
/// `scratch` (msbench's own: a staging directory, its lock file): while this object lives, a
/// signal is honoured within 0.1 s by removing `scratch` and exiting 128 + signal at once, saying
/// so on stderr. Nothing outside `scratch` may be written meanwhile (what is left of it — a file the work made while it
/// was removed — is msbench's, cleared by the next run of the command).
class ExitOnInterrupt {
 public:
  /// `empty_dirs`: directories made for the work, removed too if nothing else is in them.
  ExitOnInterrupt(std::vector<std::filesystem::path> scratch, std::string who,
                  std::vector<std::filesystem::path> empty_dirs = {});
  /// Stops watching (the work is done; from here on, safe points decide).
  ~ExitOnInterrupt();
  ExitOnInterrupt(const ExitOnInterrupt&) = delete;
  ExitOnInterrupt& operator=(const ExitOnInterrupt&) = delete;

 private:
  std::atomic<bool> done_{false};
  std::thread watcher_;
};

}  // namespace msb
