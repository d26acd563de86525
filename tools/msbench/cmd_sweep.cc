// msbench sweep: a sweep file's runs as separate processes, N at a time, into one directory
// (docs/sweeps.md; the runner is tools/sweep/sweep_runner). Resumable; --task-index runs one run
// (a Slurm array task); --emit-slurm prints the job-array script.
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/common/strict_number.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/sweep_plan.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/output_files.h"
#include "tools/sweep/sweep_runner.h"

namespace msb {

namespace fs = std::filesystem;

int runSweepCommand(int argc, char** argv) {
  ArgParser args("msbench sweep",
                 "Run a sweep file's runs (base scenario x axes x seeds) as separate processes, N at a\n"
                 "time, into DIR: sweep.json and runs.csv (index), runs/<id>/ (outputs), logs/<id>.log.\n"
                 "Re-running resumes: complete runs are skipped, failed or unfinished ones redone.");
  args.positional("SWEEP.yaml", "sweep file (see scenarios/sweeps/)")
      .option("out", "", "sweep directory", false)
      .option("jobs", "1", "runs at a time (processes)")
      .flag("list", "print the run ids in order and exit")
      .option("task-index", "", "run only run K of the list (0-based; default $SLURM_ARRAY_TASK_ID if set)")
      .flag("emit-slurm", "prepare --out and print an sbatch script that runs the sweep as a job array, and exit")
      .flag("accept-changes", "resume although the sweep file or the msbench build changed")
      .option("run-time-limit", "",
              "wall-clock seconds a run may take before the sweep stops it and records it as failed\n"
              "(default: 10x its simulated duration + 600 s; 0: no limit)");
  if (!args.parse(argc, argv)) return kExitOk;
  const SweepPlan plan = loadSweepPlan(args.get("SWEEP.yaml"));
  if (args.has("list")) {
    for (const auto& r : plan.runs) std::printf("%s\n", r.id.c_str());
    return kExitOk;
  }
  if (args.get("out").empty()) throw UsageError("--out DIR is required (except with --list)");
  if (args.has("emit-slurm")) {
    std::fputs(prepareSlurmSweep(plan, outputPathOf(args.get("out")), fs::canonical("/proc/self/exe").string(),
                                 args.has("accept-changes"))
                   .c_str(),
               stdout);
    return kExitOk;
  }
  // Distributed: exactly one run of the list (a Slurm array task); no index is written (tasks
  // run concurrently); a later plain call skips the complete runs and writes it.
  SweepRunOptions options;
  std::string task_text = args.get("task-index");
  if (task_text.empty() && std::getenv("SLURM_ARRAY_TASK_ID")) task_text = std::getenv("SLURM_ARRAY_TASK_ID");
  if (!task_text.empty()) {
    int64_t k = -1;
    std::string why;
    if (!parseInteger(task_text, &k, &why) || k < 0 || size_t(k) >= plan.runs.size())
      throw UsageError("--task-index must be in [0, " + std::to_string(plan.runs.size() - 1) + "], got '" + task_text +
                       "'");
    options.task = size_t(k);
  }
  options.jobs = args.getIntIn("jobs", 1, 256);
  options.accept_changes = args.has("accept-changes");
  std::optional<double> limit;
  if (args.given("run-time-limit")) limit = args.getDoubleIn("run-time-limit", 0.0, 1e7);
  // Every run's scenario must load before anything starts (unknown keys, bad values: exit 2).
  for (const auto& r : plan.runs) {
    std::vector<std::string> sets;
    for (const auto& [k, v] : r.sets) sets.push_back(k + "=" + v);
    try {
      const ScenarioSpec spec = loadScenario(r.scenario, sets);
      options.time_limit_s.push_back(limit ? *limit : defaultRunTimeLimitS(spec.flight.duration_s));
      // A held-out world needs the evaluator's salt before any run starts.
      if (spec.flight.held_out) {
        try {
          (void)heldOutSalt();
        } catch (const std::runtime_error& e) {
          throw std::runtime_error(std::string("key 'held_out': ") + e.what());
        }
      }
    } catch (const std::exception& e) {
      throw FileConfigError(plan.file + ": run " + r.id + ": " + e.what());
    }
  }
  const fs::path dir = outputPathOf(args.get("out"));  // where the checks look is where it writes
  const SweepOutcome outcome = runSweep(plan, dir, options, [] { return interruptRequested(); });
  if (outcome.interrupted) throwIfInterrupted();  // exit 130/143
  if (options.task) {
    std::printf("sweep task %zu: run %s %s\n", *options.task, plan.runs[*options.task].id.c_str(),
                outcome.task_status.c_str());
    return outcome.task_status == "complete" ? kExitOk : kExitRuntime;
  }
  std::printf("sweep: %zu of %zu runs complete, %zu failed -> %s\n", outcome.complete, plan.runs.size(), outcome.failed,
              (dir / "runs.csv").c_str());
  return outcome.failed ? kExitRuntime : kExitOk;
}

}  // namespace msb
