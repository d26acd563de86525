// MuJoCo reports errors and warnings through two process-wide hooks. Left unset, an error prints,
// writes MUJOCO_LOG.TXT into the current directory, waits for Enter and exits; a warning writes
// the log file too. msbench sets both (installMujocoHandlers): an error becomes a MujocoError
// exception (the caller names the file: exit 2 for a model that does not load, 1 during a run),
// and a warning is printed once per distinct text on standard error. MuJoCo counts warnings
// itself in mjData::warning; mujocoWarningCounts() reads those counters for metrics.json.
#pragma once

#include <mujoco/mujoco.h>

#include <map>
#include <stdexcept>
#include <string>

namespace msb {

/// A MuJoCo error (mju_error), thrown by the installed handler.
class MujocoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Installs msbench's MuJoCo error and warning handlers (idempotent; single-threaded use).
void installMujocoHandlers();

/// MuJoCo's warning counters of `d` that are non-zero, by name ("contact_full": 3, ...).
std::map<std::string, int> mujocoWarningCounts(const mjData* d);

}  // namespace msb
