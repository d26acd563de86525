// msbench export RUN --out DIR: a finished run in the formats the field's tools read
// (docs/interop.md) — truth.tum and estimate.tum (evo), map.bt (octovis, liboctomap) when the
// run's method left its OctoMap — and export.json saying what each file is and in which frame.
// The run directory is only read; the output is a staged directory of its own.
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/common/input_file.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/results/output_files.h"
#include "tools/results/trajectory_export.h"

namespace fs = std::filesystem;

namespace msb {

int runExportCommand(int argc, char** argv) {
  ArgParser args("msbench export",
                 "A finished run in the formats of the field's tools (docs/interop.md): truth.tum and\n"
                 "estimate.tum (TUM: timestamp tx ty tz qx qy qz qw; evo_ape tum truth.tum estimate.tum),\n"
                 "map.bt (the method's OctoMap, when it has one: octovis) and export.json (what each is).");
  args.positional("RUN", "a run's result directory (msbench run --out)")
      .option("out", "", "output directory", true)
      .flag("overwrite", "replace an existing export directory");
  if (!args.parse(argc, argv)) return kExitOk;
  const fs::path run = args.get("RUN");
  if (!isMsbenchOutput(run, OutputKind::kRun))
    throw UsageError("RUN: '" + run.string() + "' is not a run directory msbench wrote (msbench run --out)");
  checkNoOverlap({{"RUN", run}}, {{"--out", args.get("out")}});
  // Everything read and converted before the output exists: a bad run writes nothing.
  const fs::path csv = run / "trajectory.csv";
  const TumTrajectories tum = tumFromTrajectoryCsv(readInputFile(csv), csv.string());
  const bool has_bt = fs::is_regular_file(run / "map.bt");
  nlohmann::ordered_json j;
  j["run"] = fs::absolute(run).lexically_normal().string();
  j["poses"] = tum.rows;
  j["files"]["truth.tum"] = "the true body pose, world frame (ROS map), REP-103 axes (x forward, z up); s, m";
  if (!tum.estimate.empty())
    j["files"]["estimate.tum"] = "the VIO's body pose, its drifting frame (ROS odom), as the controller flew on it";
  else
    j["not_exported"]["estimate.tum"] = "trajectory.csv predates the VIO's full orientation (est_qw..est_qz)";
  if (has_bt)
    j["files"]["map.bt"] = "the method's OctoMap at the end (liboctomap binary), VIO frame (ROS odom)";
  else
    j["not_exported"]["map.bt"] = "the run's method keeps no OctoMap (map.ply holds its map)";
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kExport);
  writeFileAtomic(out.staging() / "truth.tum", tum.truth);
  if (!tum.estimate.empty()) writeFileAtomic(out.staging() / "estimate.tum", tum.estimate);
  if (has_bt) copyInputFile(run / "map.bt", out.staging() / "map.bt", [] {});
  writeFileAtomic(out.staging() / "export.json", j.dump(2) + "\n");
  out.commit();
  std::printf("export: %d poses%s -> %s\n", tum.rows, has_bt ? ", map.bt" : "", args.get("out").c_str());
  return kExitOk;
}

}  // namespace msb
