// msbench: the command-line entry point. Dispatches to sub-commands; maps errors to exit codes
// (1 runtime failure, 2 usage or configuration error).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <string>

#include <opencv2/core.hpp>

#include "core/common/config_check.h"
#include "core/explorer/method_registry.h"
#include "tools/config/flight_yaml.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/crash_handler.h"
#include "tools/msbench/interrupt.h"

namespace {

struct Command {
  const char* name;
  int (*run)(int, char**);
  const char* summary;
};

constexpr Command kCommands[] = {
    {"run", msb::runRunCommand, "run one exploration mission from a scenario; write results"},
    {"export", msb::runExportCommand, "a run's trajectories as TUM files and its OctoMap as .bt (docs/interop.md)"},
    {"video", msb::runVideoCommand, "add video.mp4 to a finished run (replays it; the hash must match)"},
    {"methods", msb::runMethodsCommand, "the registered exploration methods, their Table I rows and keys"},
    {"keys", msb::runKeysCommand, "every configuration key, its default and the values it accepts"},
    {"sweep", msb::runSweepCommand, "run a sweep file's runs (axes x seeds) in parallel processes; resumable"},
    {"report", msb::runReportCommand, "Table I layout, CSV and figures of a sweep directory"},
    {"regress", msb::runRegressCommand, "compare a sweep with a golden (exact on the same machine, else a band)"},
    {"fly", msb::runFlyCommand, "fly a scripted waypoint list in a world; write results"},
    {"vio-eval", msb::runVioEvalCommand, "fly with tracker + SLAM points, evaluate against truth"},
    {"map-replay", msb::runMapReplayCommand, "run the mapper over a recorded perception log"},
    {"grid-audit", msb::runGridAuditCommand, "replay a grid-baseline collision's log: what cleared the cells it hit"},
    {"bench-map", msb::runBenchMapCommand, "mapper time per update on a perception log"},
    {"render-probe", msb::runRenderProbeCommand, "render one fisheye frame from a pose"},
    {"bench-loop", msb::runBenchLoopCommand, "closed-loop cost per stage (per simulated s and per frame)"},
    {"bench-sim", msb::runBenchSimCommand, "physics steps/s and fisheye frame cost"},
    {"world", msb::runWorldCommand, "list, build (into the cache), show, import and export the worlds"},
};

void printUsage() {
  std::printf(
      "usage: msbench COMMAND [options]   (msbench COMMAND --help for details)\n\n"
      "msbench - deterministic headless closed-loop benchmark for monocular UAV "
      "exploration\n\ncommands:\n");
  for (const auto& c : kCommands) std::printf("  %-14s %s\n", c.name, c.summary);
  std::printf("\nexit codes: 0 ok, 1 runtime failure, 2 usage or configuration error, 130/143 interrupted\n");
}

// False, having said why on stderr, if what `who` printed did not reach stdout (`msbench keys >
// /dev/full` is an error, not an empty file).
bool stdoutWritten(const std::string& who) {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return true;
  std::fprintf(stderr, "%s: error: cannot write its output to stdout: %s\n", who.c_str(),
               std::strerror(errno ? errno : EIO));
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  // Single-threaded OpenCV inside a run (determinism; parallelism comes from processes).
  cv::setNumThreads(0);
  msb::installInterruptHandlers();
  msb::installCrashHandler(argc > 1 ? argv[1] : "");
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    printUsage();
    const bool written = stdoutWritten("msbench");
    if (argc < 2) return msb::kExitUsage;
    return written ? msb::kExitOk : msb::kExitRuntime;
  }
  for (const auto& c : kCommands) {
    if (std::strcmp(argv[1], c.name) != 0) continue;
    try {
      const int rc = c.run(argc - 2, argv + 2);
      if (!stdoutWritten(std::string("msbench ") + c.name)) return rc == msb::kExitOk ? msb::kExitRuntime : rc;
      return rc;
    } catch (const msb::Interrupted& e) {
      std::fprintf(stderr, "msbench %s: %s; stopped, no partial results left\n", c.name, e.what());
      return 128 + e.signal();
    } catch (const msb::UsageError& e) {
      std::fprintf(stderr, "msbench %s: %s\n", c.name, e.what());
      return msb::kExitUsage;
    } catch (const msb::FileConfigError& e) {
      std::fprintf(stderr, "msbench %s: %s\n", c.name, e.what());
      return msb::kExitUsage;
    } catch (const msb::MethodRegistryError& e) {
      std::fprintf(stderr, "msbench %s: the methods built into this msbench clash: %s\n", c.name, e.what());
      return msb::kExitUsage;
    } catch (const msb::ConfigError& e) {
      std::fprintf(stderr, "msbench %s: configuration error: %s\n", c.name, e.what());
      return msb::kExitUsage;
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "msbench %s: error: out of memory\n", c.name);
      return msb::kExitRuntime;
    } catch (const cv::Exception& e) {
      std::fprintf(stderr, "msbench %s: error: image processing failed (OpenCV: %s)\n", c.name, e.err.c_str());
      return msb::kExitRuntime;
    } catch (const std::filesystem::filesystem_error& e) {
      // A path msbench could not use: the path and the reason in words (a symlink loop, a file
      // where a directory is needed, no permission), as bad input.
      const std::string path = e.path1().empty() ? std::string("a path") : e.path1().string();
      std::fprintf(stderr, "msbench %s: %s: %s\n", c.name, path.c_str(), e.code().message().c_str());
      return msb::kExitUsage;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "msbench %s: error: %s\n", c.name, e.what());
      return msb::kExitRuntime;
    }
  }
  std::fprintf(stderr, "msbench: unknown command '%s'\n\n", argv[1]);
  printUsage();
  return msb::kExitUsage;
}
