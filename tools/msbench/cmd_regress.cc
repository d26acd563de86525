// msbench regress: a sweep directory against a golden file (docs/regression.md). Exit 0 when no
// run regressed, 1 when any did (each is printed), 2 on bad input. --update rewrites the golden
// from the sweep, on purpose (say why in the commit).
#include <cstdio>
#include <filesystem>

#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/results/output_files.h"
#include "tools/sweep/regression.h"

namespace msb {

namespace fs = std::filesystem;

int runRegressCommand(int argc, char** argv) {
  ArgParser args("msbench regress",
                 "Compare a sweep directory with a golden: exactly (status, A, determinism hash) for runs\n"
                 "from the golden's machine (same fingerprint), else status and A within a band. Exit 1\n"
                 "on any regression. --update writes the golden from the sweep instead.");
  args.positional("DIR", "sweep directory (from msbench sweep)")
      .option("against", "", "golden file or a directory holding golden.json", false)
      .flag("update", "write the golden from DIR (all runs must be complete)")
      .option("tolerance", "", "relative band for runs from another machine (default: the golden's, else 0.25)")
      .option("tolerance-m2", "", "absolute band in m² (default: the golden's, else 100)")
      .flag("band", "compare every run in band mode (status and A within the band), hashes and machines aside");
  if (!args.parse(argc, argv)) return kExitOk;
  fs::path golden_file = args.get("against");
  if (fs::is_directory(golden_file) || (args.has("update") && golden_file.extension() != ".json"))
    golden_file /= "golden.json";
  SweepResults results;
  try {
    results = loadSweepResults(args.get("DIR"));
  } catch (const std::filesystem::filesystem_error&) {
    throw;  // main names the path and the reason in words
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
  nlohmann::json golden;
  if (!args.has("update")) golden = readGolden(golden_file);
  // --update replaces only a golden msbench wrote, and never a file of the sweep it reads.
  if (args.has("update")) {
    const fs::path sweep = fs::weakly_canonical(fs::absolute(args.get("DIR")));
    const fs::path target = fs::weakly_canonical(fs::absolute(golden_file));
    if (target.string().rfind(sweep.string() + "/", 0) == 0)
      throw UsageError("--against " + golden_file.string() + ": inside the sweep directory " + args.get("DIR") +
                       " (an input); refusing to write there");
    if (fs::exists(golden_file) && !isGoldenFile(golden_file))
      throw UsageError("--against " + golden_file.string() +
                       ": exists and is not a golden msbench wrote; refusing to replace it");
  }
  RegressionTolerance tolerance = toleranceOf(golden);
  if (args.given("tolerance")) tolerance.relative = args.getDoubleIn("tolerance", 0.0, 10.0);
  if (args.given("tolerance-m2")) tolerance.absolute_m2 = args.getDoubleIn("tolerance-m2", 0.0, 1e6);
  tolerance.band_only = args.has("band");

  if (args.has("update")) {
    nlohmann::json g;
    try {
      g = goldenFromSweep(results, tolerance);
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "msbench regress: cannot update %s: %s\n", golden_file.c_str(), e.what());
      return kExitRuntime;
    }
    fs::create_directories(golden_file.parent_path().empty() ? fs::path(".") : golden_file.parent_path());
    const OutputLock lock(outputPathOf(golden_file), "--against");  // one writer per golden
    writeFileAtomic(golden_file, g.dump(2) + "\n");
    std::printf("regress: golden %s written from %zu runs of %s\n", golden_file.c_str(), g["runs"].size(),
                results.dir.c_str());
    return kExitOk;
  }
  const RegressionOutcome out = compareWithGolden(results, golden, tolerance);
  for (const auto& n : out.notes) std::printf("regress: note: %s\n", n.c_str());
  for (const auto& r : out.regressions) std::printf("regress: REGRESSION %s\n", r.c_str());
  std::printf(
      "regress: %d runs compared (%d exactly, %d in band mode: ±%.0f %% or %.0f m²): %s\n", out.compared, out.exact,
      out.banded, 100.0 * tolerance.relative, tolerance.absolute_m2,
      out.regressions.empty() ? "no regression" : (std::to_string(out.regressions.size()) + " regressions").c_str());
  return out.regressions.empty() ? kExitOk : kExitRuntime;
}

}  // namespace msb
