// Benchmark suites (docs/sweeps.md, "Suites"): the published runs whose settings a sweep's runs
// must share to be reported beside them.
#pragma once

#include <filesystem>

#include "tools/sweep/sweep_report.h"

namespace msb {

/// A benchmark suite (docs/sweeps.md, "Suites"): the published runs in `suite_dir` (runs/*/
/// config.yaml) fix, per world, the settings a run may fly with — the hashes of their fixed
/// settings (tools/config/scenario_yaml.h). Every complete run of `results` whose own hash
/// (metrics.json `fixed_settings_hash`, else from its config.yaml) is not among its world's is
/// set aside: status "off-suite", no record (in no row, ranking or finding), `off_suite` saying
/// why. Throws std::runtime_error when the suite has no readable run.
void applySuite(SweepResults& results, const std::filesystem::path& suite_dir);

/// The suite the complete runs name (metrics.json `suite`, from the scenario's `suite:` key):
/// "" if none names one; throws std::runtime_error if they name different suites.
std::string suiteNamedByRuns(const SweepResults& results);

}  // namespace msb
