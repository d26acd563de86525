// msbench report: the report of a sweep directory (docs/sweeps.md, "Reports"): report.md (the
// Table I layout and more), table.csv, report_runs.csv, and the figures (coverage over time per
// world, a gallery of top-down maps) drawn by the embedded Python script when python3 with
// matplotlib is available.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/output_files.h"
#include "tools/sweep/findings.h"
#include "tools/sweep/level_sweep.h"
#include "tools/sweep/suite.h"
#include "tools/sweep/sweep_report.h"

namespace msb {

extern const char* const kReportFiguresScript;  // tools/sweep/report_figures.py, embedded at build time
extern const char* const kReportHtmlScript;     // tools/sweep/report_html.py, embedded at build time

namespace {

namespace fs = std::filesystem;

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs `cmd` through /bin/sh in a process group of its own and waits for it, stopping the whole
// group (SIGTERM: the shell and the interpreter it started) and throwing Interrupted if msbench
// is signalled meanwhile, by the terminal's group signal or alone (std::system would ignore
// SIGINT and SIGQUIT while it waits). Returns the command's exit status (-1: it did not exit
// normally).
int runInterruptible(const std::string& cmd) {
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("cannot start the figure script (fork failed)");
  if (child == 0) {
    setpgid(0, 0);
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(child, child);  // also here: no window before the child's own call
  int status = 0;
  while (waitpid(child, &status, WNOHANG) == 0) {
    if (interruptRequested()) {
      kill(-child, SIGTERM);
      waitpid(child, &status, 0);
      throwIfInterrupted();
    }
    usleep(20000);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A Python interpreter that has `module` (Debian's python3-matplotlib and python3-markdown
// install for /usr/bin/python3, which a user's own python3 on PATH may not see), or "".
std::string pythonWith(const std::string& module) {
  for (const char* candidate : {"/usr/bin/python3", "python3"}) {
    const std::string cmd = std::string(candidate) + " -c 'import " + module + "' >/dev/null 2>&1";
    if (std::system(cmd.c_str()) == 0) return candidate;
  }
  return "";
}

// report.html (tools/sweep/report_html.py) into the staging directory, its links to the runs
// relative to `final_dir`; says what it did.
std::string writeHtmlPage(const StagedOutputDir& staged, const fs::path& final_dir) {
  writeFileAtomic(staged.staging() / "make_html.py", kReportHtmlScript);
  const std::string python = pythonWith("markdown");
  if (python.empty())
    return "report.html: skipped, python3-markdown not found; install it (apt-get install python3-markdown) and "
           "run: /usr/bin/python3 " +
           (final_dir / "make_html.py").string() + " " + final_dir.string();
  const std::string cmd = python + " " + shellQuote((staged.staging() / "make_html.py").string()) + " " +
                          shellQuote(staged.staging().string()) + " " + shellQuote(fs::absolute(final_dir).string()) +
                          " >/dev/null";
  if (runInterruptible(cmd) != 0) throw std::runtime_error("the report.html script failed: " + cmd);
  return "report.html";
}

}  // namespace

int runReportCommand(int argc, char** argv) {
  ArgParser args("msbench report",
                 "Report of a sweep directory: report.md (the paper's Table I layout with its figures\n"
                 "beside, box share, time to 50/90 % of the box, A per 100 m, longest time without\n"
                 "gain, collisions by object kind, RTF; 95 % bootstrap intervals over the seeds,\n"
                 "paired comparisons, the paper's findings as holds / fails / undecided; with a\n"
                 "method axis and one level axis, each method's area ratio to the first across the\n"
                 "levels), table.csv,\n"
                 "findings.csv, and figures (Table I bars with intervals, coverage over time per\n"
                 "world with a bootstrap band, a gallery of top-down maps) if python3 with\n"
                 "matplotlib is available.");
  args.positional("DIR", "sweep directory (from msbench sweep)")
      .option("out", "", "report directory (default DIR/report; an earlier report there is replaced)")
      .option("suite", "",
              "published runs whose settings the runs must share (e.g. results/table1; default: msbench's own "
              "settings, never one a run names); others are set aside")
      .option("key", "",
              "the evaluator's key file: rank only records sealed under it (docs/integrity.md); default: seals "
              "are not verified")
      .flag("no-figures", "write the Markdown and CSV files only");
  if (!args.parse(argc, argv)) return kExitOk;
  const fs::path dir = args.get("DIR");
  if (!fs::is_directory(dir)) throw UsageError(dir.string() + ": not a directory");
  SweepResults results;
  try {
    results = loadSweepResults(dir);
    // The suite given on the command line, never one the runs name for themselves.
    const std::string suite = args.get("suite");
    if (!suite.empty() && !fs::is_directory(suite))
      throw std::runtime_error("--suite " + suite + ": not a directory from here: run from the repository");
    applyRankRules(results);  // every report: only sealed, confined runs are ranked
    if (!args.get("key").empty()) {
      const SealSummary seals = applySealRules(results, readEvaluatorKey(args.get("key")));
      std::fprintf(
          stderr, "report: evaluator key %s: %d runs sealed under it, %d not (listed, not ranked)%s\n",
          seals.key_id.c_str(), seals.evaluated, seals.not_evaluated,
          seals.tampered ? (", " + std::to_string(seals.tampered) + " tampered (counted as failed)").c_str() : "");
    }
    if (!suite.empty())
      applySuite(results, suite);
    else  // the default suite: msbench's own settings, where some run flies them
      applyRetunedRule(results, [&] {
        const std::set<std::string> worlds = worldsOf(results);
        return publishedSettings(resultsDir(), &worlds);
      }());
  } catch (const std::filesystem::filesystem_error&) {
    throw;  // main names the path and the reason in words
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
  const fs::path out = args.get("out").empty() ? dir / "report" : fs::path(args.get("out"));
  const std::vector<ReportRow> rows = reportRows(results);
  throwIfInterrupted();  // safe points: after reading, after writing the tables, after the figures

  // The report may sit inside the sweep (DIR/report, the default) but never over its inputs.
  checkNoOverlap({{"DIR (sweep.json)", dir / "sweep.json"},
                  {"DIR (runs)", dir / "runs"},
                  {"DIR (runs.csv)", dir / "runs.csv"},
                  {"DIR (logs)", dir / "logs"}},
                 {{"--out", out}});
  StagedOutputDir staged(out, /*overwrite=*/true, OutputKind::kReport);
  // A sweep of methods across levels of a condition: each ablation's ratio against the level;
  // the paper's findings are checked on the first level's rows only (the paper had one).
  const std::optional<LevelSweep> levels = levelSweep(results, rows);
  const std::vector<FindingResult> findings =
      evaluateFindings(results, levels ? rowsAtLevel(results, rows, *levels, 0) : rows);
  writeFileAtomic(staged.staging() / "report.md", reportMarkdown(results, rows) +
                                                      (levels ? levelSweepMarkdown(*levels) : std::string()) +
                                                      findingsMarkdown(findings));
  if (levels) writeFileAtomic(staged.staging() / "ablation_levels.csv", levelSweepCsv(*levels));
  writeFileAtomic(staged.staging() / "findings.csv", findingsCsv(findings));
  writeFileAtomic(staged.staging() / "table.csv", reportTableCsv(results, rows));
  writeFileAtomic(staged.staging() / "report_runs.csv", reportRunsCsv(results));
  writeFileAtomic(staged.staging() / "make_figures.py", kReportFiguresScript);

  // Figures: into the staging directory, so the report appears whole or not at all.
  std::string figures = "figures: skipped (--no-figures)";
  if (!args.has("no-figures")) {
    const std::string python = pythonWith("matplotlib");
    if (python.empty()) {
      figures =
          "figures: skipped, python3 with matplotlib not found; install it (apt-get install "
          "python3-matplotlib) and run: /usr/bin/python3 " +
          (out / "make_figures.py").string() + " " + out.string();
    } else {
      const std::string cmd = python + " " + shellQuote((staged.staging() / "make_figures.py").string()) + " " +
                              shellQuote(staged.staging().string()) + " >/dev/null";
      if (runInterruptible(cmd) != 0) throw std::runtime_error("the figure script failed: " + cmd);
      figures =
          std::string("figures: coverage_<world>.png, gallery.png") + (levels ? ", ablation_levels_<world>.png" : "");
    }
  }
  throwIfInterrupted();
  const std::string page = writeHtmlPage(staged, out);
  staged.commit();
  const FindingCounts c = countFindings(findings);
  std::printf(
      "report: %zu rows from %zu runs -> %s (report.md, table.csv, findings.csv); findings %d hold, %d fail, "
      "%d undecided, %d not evaluated; %s; %s\n",
      rows.size(), results.runs.size(), out.c_str(), c.holds, c.fails, c.undecided, c.not_evaluated, figures.c_str(),
      page.c_str());
  return kExitOk;
}

}  // namespace msb
