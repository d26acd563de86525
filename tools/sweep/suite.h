// Benchmark suites (docs/sweeps.md, "Suites"): the published runs whose settings a sweep's runs
// must share to be reported beside them.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "tools/results/record_seal.h"
#include "tools/sweep/sweep_report.h"

namespace msb {

/// A benchmark suite (docs/sweeps.md, "Suites"): the published runs in `suite_dir` (runs/*/
/// config.yaml) fix, per world, the settings a run may fly with — the hashes of their fixed
/// settings (tools/config/scenario_yaml.h). Every complete run of `results` whose own hash
/// (metrics.json `fixed_settings_hash`, else from its config.yaml) is not among its world's is
/// set aside: status "off-suite", no record (in no row, ranking or finding), `off_suite` saying
/// why. Throws std::runtime_error when the suite has no readable run, or when the complete runs
/// disagree on the salt of their held-out worlds (metrics.json `world_salt_commitment`, "no salt"
/// for a run without).
void applySuite(SweepResults& results, const std::filesystem::path& suite_dir);

/// The rule of every report (docs/metrics.md, "What is ranked"): a complete run is ranked only if
/// its record is sealed and its method ran confined or compiled into msbench. An unsealed record
/// from a build that seals (it names its method's confinement, which such builds write beside
/// the seal) and a run whose method ran unconfined (in-process, a goal chooser) are set aside:
/// status "unranked" with the reason, in no row, ranking, ratio or finding.
void applyRankRules(SweepResults& results);

/// Per world, the fixed-settings hashes of a set of runs.
using SettingsByWorld = std::map<std::string, std::set<std::string>>;

/// msbench's own settings (docs/metrics.md, "What is ranked"): per world, the fixed-settings
/// hashes of every run msbench publishes (`results_dir`/*/runs/*/config.yaml, read by this build);
/// with `worlds`, of the runs in those worlds only (each config read in full only then).
SettingsByWorld publishedSettings(const std::filesystem::path& results_dir,
                                  const std::set<std::string>* worlds = nullptr);

/// The worlds of a report's runs (metrics.json `world`).
std::set<std::string> worldsOf(const SweepResults& results);

/// The default report's suite: in a world where some ranked run flies one of msbench's own
/// settings (`own`), a ranked run whose fixed settings are none of them is "retuned" — status
/// "unranked" with the reason, in no row, ranking, ratio or finding (a sweep variant with a longer
/// camera range used to outrank MonoSpheres). Worlds msbench publishes nothing in, and reports
/// whose runs in a world all fly settings of their own, are left as they are (compare those
/// under --suite).
void applyRetunedRule(SweepResults& results, const SettingsByWorld& own);

/// What applySealRules found.
struct SealSummary {
  std::string key_id;
  int evaluated = 0;      ///< ranked: sealed under the key, unchanged
  int not_evaluated = 0;  ///< self-sealed, pre-seal or another key's: listed, not ranked
  int tampered = 0;       ///< sealed under the key and changed since: counted as failed
};

/// The rule of a report under the evaluator's key (`msbench report --key`, docs/integrity.md):
/// a complete run is ranked only if its record is sealed under `key` and unchanged since. A
/// self-sealed record, one written before keyed seals (writtenBeforeKeyedSeals) and one sealed
/// under another key are set aside as "unranked" with the reason; a record whose seal names this
/// key but does not match (edited, or re-sealed by a forger) is a failed run: it counts as one
/// (score 0, A 0), never as a result. Throws std::runtime_error naming the key file when records
/// here carry keyed seals and none is under `key` (the wrong key).
SealSummary applySealRules(SweepResults& results, const EvaluatorKey& key);

}  // namespace msb
