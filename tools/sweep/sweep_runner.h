// The sweep runner (docs/sweeps.md): a sweep plan's runs as separate `msbench run` processes, N at
// a time, into one directory:
//   DIR/sweep.json   the plan (file, its hash, the msbench build) and every run's status
//   DIR/runs.csv     one row per run (status, A, box share, hashes, exit code or signal)
//   DIR/runs/<id>/   the run's outputs (metrics.json present and not an error = complete)
//   DIR/logs/<id>.log  its standard output and error (progress lines, the crash handler's report)
// A run that fails (exit code, signal) is recorded with its signal, last progress line and log
// tail, and the sweep goes on. Running again skips complete runs and redoes the others; a
// changed sweep file or msbench build is named and refused unless accepted.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tools/config/sweep_plan.h"

namespace msb {

/// How to run a sweep.
struct SweepRunOptions {
  long jobs = 1;                ///< runs at a time (processes)
  std::optional<size_t> task;   ///< run only this run of the plan (a Slurm array task); no index written
  bool accept_changes = false;  ///< resume although the sweep file or the build changed
  /// Wall-clock seconds each run may take, by plan index (empty or <= 0: no limit). A run past
  /// it gets SIGTERM, SIGKILL 30 s later, and is recorded as failed with the limit named.
  std::vector<double> time_limit_s;
};

/// The default wall-clock limit of a run of `duration_s` simulated seconds: 10× plus 10 minutes
/// (the loop runs at real-time factor ≥ 1 on this machine class; a hang never ends by itself).
double defaultRunTimeLimitS(double duration_s);

/// What a sweep call did.
struct SweepOutcome {
  size_t complete = 0, failed = 0;  ///< runs complete and failed at the end (all runs of the plan)
  bool interrupted = false;         ///< stop_requested() ended it; unfinished runs stay pending
  std::string task_status;          ///< with a task: its run's status (complete | failed | pending)
};

/// Runs `plan` into `dir` (new, or a sweep directory of the same plan and build). Polls
/// `stop_requested` while runs are going; when it returns true the running runs get SIGTERM
/// and the call returns with `interrupted`. Throws UsageError when `dir` cannot take the sweep.
SweepOutcome runSweep(const SweepPlan& plan, const std::filesystem::path& dir, const SweepRunOptions& options,
                      const std::function<bool()>& stop_requested);

/// Prepares `out` for `plan` as runSweep would (new, empty or this sweep's directory; throws
/// UsageError otherwise) with a `slurm/` folder for the tasks' logs, and returns the sbatch
/// script that runs `plan` as a job array into it, one task per run, with the executable `exe`.
std::string prepareSlurmSweep(const SweepPlan& plan, const std::filesystem::path& out, const std::string& exe,
                              bool accept_changes);

/// The build a sweep's results come from ("version+git revision").
std::string sweepBuildId();

}  // namespace msb
