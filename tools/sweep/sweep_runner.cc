#include "tools/sweep/sweep_runner.h"
#include "tools/sweep/sweep_index.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/common/config_check.h"
#include "core/common/wall_time.h"
#include "tools/results/input_files.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"
#include "tools/results/run_record.h"
#include "tools/sweep/markdown_text.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// What became of one run.
struct RunState {
  std::string status = "pending";  // pending | complete | failed
  int exit_code = 0, signal = 0;
  std::string log_tail;
  std::string last_progress;  // the run's last progress line, if it printed one
  std::string fatal;          // the crash handler's line (signal, tick, simulated time)
  std::string limit;          // the sweep stopped it at its wall-clock limit
  nlohmann::json metrics;     // the run's metrics.json (complete runs)
};

std::string tail(const std::string& text, int lines) {
  if (text.empty()) return text;  // a run killed before it wrote anything
  size_t pos = text.size();
  for (int k = 0; k <= lines && pos > 0; ++k) {
    const size_t nl = text.rfind('\n', pos - 1);
    if (nl == std::string::npos) return text;
    pos = nl;
  }
  return text.substr(pos + 1);
}

// The last line of `text` that contains `marker` ("" if none).
std::string lastLineWith(const std::string& text, const std::string& marker) {
  const size_t at = text.rfind(marker);
  if (at == std::string::npos) return "";
  const size_t begin = text.rfind('\n', at);
  const size_t end = text.find('\n', at);
  return text.substr(begin == std::string::npos ? 0 : begin + 1,
                     (end == std::string::npos ? text.size() : end) - (begin == std::string::npos ? 0 : begin + 1));
}

// A run's outputs are complete when its metrics.json reads as a complete record (the strict
// reader of tools/results/run_record.h): a missing, truncated or incomplete file, or the record
// of a run that ended in an error (msbench run writes one then, and exits 1), is redone.
std::optional<nlohmann::json> completeMetrics(const fs::path& file) {
  MissionRecordRead read = readMissionRecord(file);
  if (!read.record) return std::nullopt;
  return std::move(read.record->metrics);
}

// The build a sweep's results come from.
std::string buildIdText() {
  const auto v = versionInfo();
  return v.value("msbench", std::string("?")) + "+" + v.value("git_revision", std::string("?"));
}

// Starts `msbench run` for one run; stdout and stderr go to its log. Returns the child's pid.
pid_t startRun(const SweepRun& run, const fs::path& out, const fs::path& log) {
  std::vector<std::string> args = {"msbench", "run", run.scenario, "--seed", std::to_string(run.seed)};
  for (const auto& [k, v] : run.sets) args.insert(args.end(), {"--set", k + "=" + v});
  // Not --quiet: the log keeps a progress line every 10 simulated seconds, so a failed run's log
  // says how far it got.
  args.insert(args.end(), {"--out", out.string(), "--overwrite"});
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    // The log: a regular file or nothing. A FIFO or device put there is never opened for
    // writing (it would block); the run fails and the sweep's record names the log.
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC, 0644);
    struct stat st {};
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) _exit(126);
    if (ftruncate(fd, 0) != 0) _exit(126);
    dup2(fd, 1), dup2(fd, 2), close(fd);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  return pid;
}

std::string csvRow(const SweepRun& r, const RunState& s, const std::vector<std::string>& axes) {
  std::ostringstream o;
  o << csvField(r.id);
  for (const auto& a : axes) o << "," << csvField(r.labels.at(a));
  const auto& m = s.metrics;
  auto num = [&](const nlohmann::json& j) { return j.is_number() ? std::to_string(j.get<double>()) : std::string(); };
  o << "," << r.seed << "," << s.status << "," << (m.is_object() ? m.value("status", "") : "") << ","
    << (m.is_object() ? num(m["coverage"]["area_m2"]) : "") << ","
    << (m.is_object() ? num(m["coverage"]["box_share"]) : "") << "," << (m.is_object() ? num(m["sim_time_s"]) : "")
    << "," << (m.is_object() ? num(m["wall_time_s"]) : "") << ","
    << (m.is_object() ? m.value("determinism_hash", "") : "") << "," << s.exit_code << "," << s.signal << ","
    << (m.is_object() ? num(m["coverage"]["verified_area_m2"]) : "") << ","
    << (m.is_object() ? num(m["coverage"]["verified_box_share"]) : "") << ","
    << (m.is_object() && m.contains("score") && m["score"].is_object()
            ? num(m["score"].value("earned", nlohmann::json()))
            : "")
    << "\n";
  return o.str();
}

// Writes sweep.json and runs.csv (atomically) for the current states.
void writeIndex(const fs::path& dir, const SweepPlan& plan, const std::vector<RunState>& states, int jobs) {
  nlohmann::json runs = nlohmann::json::array();
  std::string csv = "id";
  for (const auto& a : plan.axes) csv += "," + a;
  csv +=
      ",seed,status,run_status,area_m2,box_share,sim_time_s,wall_time_s,determinism_hash,exit_code,signal,"
      "verified_area_m2,verified_box_share,score_earned_m3\n";
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    const SweepRun& r = plan.runs[i];
    const RunState& s = states[i];
    SweepRunRecord rec;
    rec.id = r.id;
    rec.seed = r.seed;
    rec.scenario = r.scenario;
    rec.labels = r.labels;
    for (const auto& [k, v] : r.sets) rec.sets.push_back(k + "=" + v);
    rec.status = s.status == "complete" ? SweepRunStatus::kComplete
                 : s.status == "failed" ? SweepRunStatus::kFailed
                                        : SweepRunStatus::kPending;
    if (rec.status == SweepRunStatus::kFailed) {
      SweepRunFailure f;
      f.exit_code = s.exit_code, f.signal = s.signal, f.log_tail = s.log_tail;
      if (s.signal) f.signal_name = sigabbrev_np(s.signal) ? std::string("SIG") + sigabbrev_np(s.signal) : "?";
      f.last_progress = s.last_progress, f.fatal = s.fatal, f.limit = s.limit;
      rec.failure = f;
    }
    if (s.metrics.is_object() && s.metrics["coverage"]["area_m2"].is_number()) {
      rec.area_m2 = s.metrics["coverage"]["area_m2"].get<double>();
      rec.run_status = s.metrics.value("status", "");
    }
    const nlohmann::json j = sweepRunJson(rec);
    runs.push_back(j);
    csv += csvRow(r, s, plan.axes);
  }
  const nlohmann::json index = {{"sweep_file", plan.file},
                                {"sweep_file_hash", plan.file_hash},
                                {"build", sweepBuildId()},
                                {"versions", versionInfo()},
                                {"jobs", jobs},
                                {"axes", plan.axes},
                                {"runs", runs}};
  writeFileAtomic(dir / "sweep.json", index.dump(2) + "\n");
  writeFileAtomic(dir / "runs.csv", csv);
}

}  // namespace

std::string sweepBuildId() { return buildIdText(); }

double defaultRunTimeLimitS(double duration_s) { return 10.0 * duration_s + 600.0; }

namespace {

constexpr char kSweepMarker[] = ".msbench-sweep";

// True if msbench wrote `dir` as a sweep directory: its marker, or (a sweep from before the
// marker) a sweep index with its runs, build and sweep-file hash.
bool isSweepDir(const fs::path& dir) {
  if (fs::exists(dir / kSweepMarker)) return true;
  try {
    const auto j = readJsonFile(dir / "sweep.json");
    return j.is_object() && j.contains("runs") && j.contains("build") && j.contains("sweep_file_hash");
  } catch (const InputFileError&) {
    return false;
  }
}

// No input of the sweep (its file, the runs' scenarios) is one of the files the sweep writes.
void checkSweepInputs(const SweepPlan& plan, const fs::path& dir) {
  std::vector<NamedPath> inputs = {{"SWEEP", plan.file}};
  for (const auto& r : plan.runs)
    if (inputs.back().path != r.scenario) inputs.push_back({"the scenario of run " + r.id, r.scenario});
  std::vector<NamedPath> outputs;
  for (const char* f : {"sweep.json", "runs.csv", "runs", "logs", "slurm", kSweepMarker})
    outputs.push_back({"--out " + (dir / f).string(), dir / f});
  checkNoOverlap(inputs, outputs);
}

// The directory: new or empty, or one msbench wrote as a sweep (resume: of the same file and
// build; --accept-changes mixes). Anything else is refused before a file is written.
void prepareSweepDir(const SweepPlan& plan, const fs::path& dir, const SweepRunOptions& options) {
  // A symlink is never followed (as for every output): the user names the directory itself.
  if (fs::is_symlink(dir))
    throw UsageError("--out " + dir.string() + ": is a symbolic link; give the directory it leads to");
  if (fs::exists(fs::symlink_status(dir)) && !fs::is_directory(dir))
    throw UsageError("--out " + dir.string() + ": exists and is not a directory");
  checkSweepInputs(plan, dir);
  if (fs::exists(dir) && !fs::is_empty(dir) && !isSweepDir(dir))
    throw UsageError("--out " + dir.string() +
                     ": exists, is not empty and is not a sweep directory msbench wrote (no " + kSweepMarker +
                     " or sweep.json index); use a new or empty directory");
  if (!options.task && fs::exists(dir / "sweep.json")) {
    const auto old = readJsonFile(dir / "sweep.json");
    if (!old.is_object()) throw UsageError(dir.string() + "/sweep.json is not a JSON object: not a sweep directory?");
    for (const char* key : {"sweep_file_hash", "build"})
      if (old.contains(key) && !old[key].is_string())
        throw UsageError((dir / "sweep.json").string() + ": key '" + key + "': expected a string");
    std::vector<std::string> changes;
    if (old.value("sweep_file_hash", "") != plan.file_hash)
      changes.push_back("the sweep file changed (" + plan.file + ")");
    if (old.value("build", "") != sweepBuildId())
      changes.push_back("the msbench build changed (" + old.value("build", "?") + " -> " + sweepBuildId() + ")");
    if (!changes.empty() && !options.accept_changes) {
      std::string msg = "cannot resume " + dir.string() + " (its index " + (dir / "sweep.json").string() + " records";
      msg += " another sweep file or build):";
      for (const auto& c : changes) msg += " " + c + ";";
      throw UsageError(msg + " use a new --out, or --accept-changes to mix results");
    }
    for (const auto& c : changes) std::fprintf(stderr, "sweep: resuming although %s\n", c.c_str());
  }
  fs::create_directories(dir / "runs");
  fs::create_directories(dir / "logs");
  if (!fs::exists(dir / kSweepMarker))
    writeFileAtomic(dir / kSweepMarker, "This directory was written by msbench (sweep); a sweep resumes here.\n");
}

// Records how run `i` ended (`wstatus` from waitpid): complete, pending (we stopped it) or failed
// with its exit code or signal, log tail, last progress line and the crash handler's line.
void recordRunEnd(const SweepPlan& plan, const fs::path& dir, size_t i, int wstatus, bool interrupted, RunState& s,
                  size_t& failed) {
  const fs::path m = dir / "runs" / plan.runs[i].id / "metrics.json";
  s.exit_code = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 0;
  s.signal = WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0;
  auto metrics = WIFEXITED(wstatus) && s.exit_code == 0 ? completeMetrics(m) : std::nullopt;
  if (metrics) {
    s.status = "complete";
    s.metrics = std::move(*metrics);
  } else if (interrupted) {
    s.status = "pending";  // stopped by us: redone on resume
  } else {
    s.status = "failed";
    std::string log;
    try {
      log = readInputFile(dir / "logs" / (plan.runs[i].id + ".log"));
    } catch (const InputFileError& e) {
      log = e.what();
    }
    s.log_tail = tail(log, 12);
    s.last_progress = lastLineWith(log, ": t = ");
    s.fatal = lastLineWith(log, ": fatal signal ");
    ++failed;
    std::fprintf(stderr, "sweep: run %s failed (%s %d); see %s\n", plan.runs[i].id.c_str(),
                 s.signal ? "signal" : "exit code", s.signal ? s.signal : s.exit_code,
                 (dir / "logs" / (plan.runs[i].id + ".log")).c_str());
  }
}

}  // namespace

SweepOutcome runSweep(const SweepPlan& plan, const fs::path& dir, const SweepRunOptions& options,
                      const std::function<bool()>& stop_requested) {
  // One sweep writes a directory's index (Slurm tasks, which write no index, run side by side).
  std::optional<OutputLock> lock;
  if (!options.task) {
    if (dir.has_parent_path()) fs::create_directories(dir.parent_path());
    lock.emplace(outputPathOf(dir), "--out");
  }
  // The directory: new, or a sweep of the same file and build (resume).
  prepareSweepDir(plan, dir, options);
  // Complete runs are skipped.
  std::vector<RunState> states(plan.runs.size());
  std::vector<size_t> todo;
  for (size_t i = 0; i < plan.runs.size(); ++i) {
    const fs::path m = dir / "runs" / plan.runs[i].id / "metrics.json";
    if (options.task && i != *options.task) continue;  // another task's run
    if (auto metrics = completeMetrics(m)) {
      states[i].status = "complete";
      states[i].metrics = std::move(*metrics);
    } else {
      todo.push_back(i);
    }
  }
  if (!options.task) writeIndex(dir, plan, states, int(options.jobs));
  const size_t skipped = (options.task ? 1 : plan.runs.size()) - todo.size();
  std::fprintf(stderr, "sweep %s: %zu runs (%zu complete, %zu to run), %ld at a time -> %s\n", plan.file.c_str(),
               plan.runs.size(), skipped, todo.size(), options.jobs, dir.string().c_str());

  // The pool: start runs in order, N at a time; record each as it ends.
  std::map<pid_t, size_t> running;
  std::map<pid_t, WallClock::time_point> started;  // the watchdog's clock (wall time decides nothing else)
  std::map<pid_t, WallClock::time_point> stopped;  // runs past their limit: SIGTERM sent at
  auto limitOf = [&](size_t i) { return i < options.time_limit_s.size() ? options.time_limit_s[i] : 0.0; };
  // Stops runs past their wall-clock limit: SIGTERM, then SIGKILL if it has not ended 30 s later.
  auto watchdog = [&]() {
    for (const auto& [p, i] : running) {
      const double limit = limitOf(i);
      if (limit <= 0.0) continue;
      if (!stopped.count(p) && secondsSince(started[p]) > limit) {
        std::fprintf(stderr, "sweep: run %s passed its wall-clock limit of %.0f s; stopping it\n",
                     plan.runs[i].id.c_str(), limit);
        kill(p, SIGTERM);
        stopped[p] = WallClock::now();
      } else if (stopped.count(p) && secondsSince(stopped[p]) > 30.0) {
        kill(p, SIGKILL);
      }
    }
  };
  size_t next = 0, failed = 0, done = 0;
  const auto t0 = WallClock::now();
  auto progress = [&]() {
    const double elapsed = secondsSince(t0);
    const double eta = done > 0 ? elapsed / double(done) * double(todo.size() - done) : 0.0;
    std::fprintf(stderr, "sweep: %zu done, %zu running, %zu failed of %zu (%zu skipped); %.0f s elapsed%s\n", done,
                 running.size(), failed, todo.size(), skipped, elapsed,
                 done > 0 ? (", ETA " + std::to_string(int(eta)) + " s").c_str() : "");
  };
  bool interrupted = false;
  while ((next < todo.size() && !interrupted) || !running.empty()) {
    while (!interrupted && next < todo.size() && running.size() < size_t(options.jobs)) {
      const size_t i = todo[next++];
      const SweepRun& r = plan.runs[i];
      const pid_t p = startRun(r, dir / "runs" / r.id, dir / "logs" / (r.id + ".log"));
      running[p] = i;
      started[p] = WallClock::now();
    }
    int wstatus = 0;
    const pid_t pid = waitpid(-1, &wstatus, WNOHANG);
    if (pid <= 0) {
      watchdog();
      if (!interrupted && stop_requested()) {
        interrupted = true;
        for (const auto& [p, i] : running) kill(p, SIGTERM);  // each run cleans up its own outputs
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const size_t i = it->second;
    running.erase(it);
    // A Ctrl-C reaches the whole process group: the run it stopped is interrupted, not failed,
    // and no new run starts (the stop is seen before the run's end is recorded).
    if (!interrupted && stop_requested()) {
      interrupted = true;
      for (const auto& [p, j] : running) kill(p, SIGTERM);
    }
    const bool past_limit = stopped.erase(pid) > 0;
    started.erase(pid);
    recordRunEnd(plan, dir, i, wstatus, interrupted && !past_limit, states[i], failed);
    if (past_limit && states[i].status == "failed") {
      char why[160];
      std::snprintf(why, sizeof(why), "stopped by the sweep: its wall-clock limit of %.0f s passed", limitOf(i));
      states[i].limit = why;
    }
    ++done;
    if (!options.task) writeIndex(dir, plan, states, int(options.jobs));
    progress();
  }
  if (!options.task) writeIndex(dir, plan, states, int(options.jobs));
  SweepOutcome outcome;
  outcome.interrupted = interrupted;
  for (const auto& s : states) outcome.complete += s.status == "complete", outcome.failed += s.status == "failed";
  if (options.task) outcome.task_status = states[*options.task].status;
  return outcome;
}

std::string prepareSlurmSweep(const SweepPlan& plan, const fs::path& out, const std::string& exe, bool accept_changes) {
  // The directory is checked and marked now: Slurm writes the tasks' logs into out/slurm before
  // the first task starts, and needs that folder to exist.
  SweepRunOptions options;
  options.accept_changes = accept_changes;
  prepareSweepDir(plan, out, options);
  fs::create_directories(out / "slurm");
  // One array task per run, one core each; afterwards a plain `sweep` call writes the index.
  char text[4096];
  std::snprintf(text, sizeof(text),
                "#!/bin/bash\n#SBATCH --job-name=msbench-sweep\n#SBATCH --array=0-%zu\n#SBATCH --cpus-per-task=1\n"
                "#SBATCH --output=%s/slurm/slurm-%%A_%%a.out\n"
                "'%s' sweep '%s' --out '%s' --task-index \"$SLURM_ARRAY_TASK_ID\"\n"
                "# when all tasks are done: '%s' sweep '%s' --out '%s'   (writes sweep.json and runs.csv)\n",
                plan.runs.size() - 1, out.c_str(), exe.c_str(), plan.file.c_str(), out.c_str(), exe.c_str(),
                plan.file.c_str(), out.c_str());
  return text;
}

}  // namespace msb
