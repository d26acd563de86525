#include "tools/sweep/suite.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/common/input_file.h"
#include "tools/config/scenario_yaml.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// (world, fixed-settings hash) of the scenario in a run's config.yaml.
std::pair<std::string, std::string> settingsOf(const fs::path& config) {
  const ScenarioSpec spec = loadScenario(config.string());
  return {spec.flight.world_name.empty() ? spec.flight.world_path : spec.flight.world_name, spec.fixed_settings_hash};
}

// The world a msbench-written config.yaml names on its top-level `world:` line ("" if none).
std::string worldLineOf(const fs::path& config) {
  std::ifstream in(config);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("world: ", 0) == 0) return line.substr(7);
  return "";
}

// Per world, the fixed-settings hashes of the runs under `runs_dir` (each run's config.yaml);
// with `worlds`, only of runs whose config names one of them.
void addSettingsOfRuns(const fs::path& runs_dir, SettingsByWorld& out, const std::set<std::string>* worlds = nullptr) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(runs_dir, ec)) {
    if (!fs::is_regular_file(e.path() / "config.yaml")) continue;
    if (worlds && !worlds->count(worldLineOf(e.path() / "config.yaml"))) continue;
    try {
      const auto [world, hash] = settingsOf(e.path() / "config.yaml");
      out[world].insert(hash);
    } catch (const std::exception&) {
      // A published run this build cannot read: its settings are not msbench's own any more.
    }
  }
}

// A run's fixed-settings hash: its record's, else from its config.yaml ("" when unreadable).
std::string hashOfRun(const SweepResults& results, const ReportRun& run) {
  const nlohmann::json& m = run.metrics;
  if (m.contains("fixed_settings_hash") && m["fixed_settings_hash"].is_string())
    return m["fixed_settings_hash"].get<std::string>();
  try {
    return settingsOf(results.dir / "runs" / run.id / "config.yaml").second;
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace

SettingsByWorld publishedSettings(const fs::path& results_dir, const std::set<std::string>* worlds) {
  SettingsByWorld out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(results_dir, ec))
    if (e.is_directory()) addSettingsOfRuns(e.path() / "runs", out, worlds);
  return out;
}

std::set<std::string> worldsOf(const SweepResults& results) {
  std::set<std::string> out;
  for (const ReportRun& run : results.runs)
    if (run.metrics.is_object()) out.insert(run.metrics.value("world", std::string("?")));
  return out;
}

void applyRetunedRule(SweepResults& results, const SettingsByWorld& own) {
  // Per world: the hashes of the runs still ranked.
  std::map<std::string, std::vector<std::pair<ReportRun*, std::string>>> by_world;
  for (ReportRun& run : results.runs)
    if (run.status == "complete" && run.metrics.is_object())
      by_world[run.metrics.value("world", std::string("?"))].push_back({&run, hashOfRun(results, run)});
  for (auto& [world, runs] : by_world) {
    const auto it = own.find(world);
    if (it == own.end()) continue;  // a world msbench publishes nothing in: no default
    const std::set<std::string>& mine = it->second;
    const bool some_own = std::any_of(runs.begin(), runs.end(), [&](const auto& r) { return mine.count(r.second); });
    if (!some_own) continue;  // every run flies settings of its own: compared like with like
    for (auto& [run, hash] : runs) {
      if (hash.empty() || mine.count(hash)) continue;
      run->unranked = "retuned: its fixed settings " + hash + " are none of msbench's own for " + world +
                      ", which other runs here fly (compare them under --suite)";
      run->status = "unranked";
      run->record.reset();
    }
  }
}

void applySuite(SweepResults& results, const fs::path& suite_dir) {
  // The suite: per world, the hashes its published runs flew with.
  SettingsByWorld allowed;
  addSettingsOfRuns(suite_dir / "runs", allowed);
  if (allowed.empty())
    throw std::runtime_error("--suite " + suite_dir.string() + ": no run with a readable config.yaml under runs/");
  // Held-out worlds: one salt for every run the suite ranks (records carry its commitment).
  std::set<std::string> salts;
  for (const ReportRun& run : results.runs)
    if (run.record) {
      const auto it = run.metrics.find("world_salt_commitment");
      salts.insert(it != run.metrics.end() && it->is_string() ? it->get<std::string>() : "no salt");
    }
  if (salts.size() > 1)
    throw std::runtime_error("--suite " + suite_dir.string() + ": the runs were drawn with " +
                             std::to_string(salts.size()) + " different world salts (" + *salts.begin() + ", " +
                             *std::next(salts.begin()) + (salts.size() > 2 ? ", ..." : "") +
                             "): a suite ranks the runs of one salt; report each salt's runs apart");
  results.suite = suite_dir.string();
  for (ReportRun& run : results.runs) {
    if (!run.record) continue;
    const std::string world = run.metrics.value("world", std::string("?"));
    std::string hash;
    try {
      hash = run.metrics.contains("fixed_settings_hash") && run.metrics["fixed_settings_hash"].is_string()
                 ? run.metrics["fixed_settings_hash"].get<std::string>()
                 : settingsOf(results.dir / "runs" / run.id / "config.yaml").second;
    } catch (const std::exception& e) {
      run.off_suite = std::string("its settings cannot be read: ") + e.what();
    }
    if (run.off_suite.empty() && !allowed.count(world))
      run.off_suite = "world " + world + " is not in the suite";
    else if (run.off_suite.empty() && !allowed[world].count(hash))
      run.off_suite = "fixed settings " + hash + " differ from the suite's for " + world + " (" + [&] {
        std::string s;
        for (const auto& h : allowed[world]) s += (s.empty() ? "" : ", ") + h;
        return s;
      }() + ")";
    if (run.off_suite.empty()) continue;
    run.status = "off-suite";
    run.record.reset();
  }
}

void applyRankRules(SweepResults& results) {
  for (ReportRun& run : results.runs) {
    if (run.status != "complete" || !run.metrics.is_object()) continue;
    const nlohmann::json& m = run.metrics;
    const std::string confinement = m.contains("method_confinement") && m["method_confinement"].is_string()
                                        ? m["method_confinement"].get<std::string>()
                                        : "";
    // Which seals the record must carry is decided by the build that wrote it (its version).
    const bool keyed_build = !writtenBeforeKeyedSeals(m);
    if ((keyed_build || !confinement.empty()) && !m.contains("record_digest"))
      run.unranked = "unsealed: its record has no record_digest, which every build that records confinement writes";
    else if (keyed_build && !m.contains("record_seal"))
      run.unranked = "unsealed: its record has no record_seal, which every build since record_format 2 writes";
    else if (confinement.find("unconfined") != std::string::npos || confinement.find("in-process") != std::string::npos)
      run.unranked = "unconfined: its method ran " + confinement;
    if (run.unranked.empty()) continue;
    run.status = "unranked";
    run.record.reset();
  }
}

namespace {

// Why a record not sealed under the evaluator's key is not ranked as evaluated.
std::string notEvaluatedReason(SealCheck check, const nlohmann::json& m) {
  switch (check) {
    case SealCheck::kSelfSealed:
      return "self-sealed: written without the evaluator's key";
    case SealCheck::kPreSeal:
      return "pre-seal: written by msbench " +
             (m.contains("versions") && m["versions"].is_object() ? m["versions"].value("msbench", std::string("?"))
                                                                  : std::string("?")) +
             ", before keyed seals";
    case SealCheck::kOtherKey:
      return "sealed under another evaluator key (" + sealKeyId(m) + ")";
    default:
      return "";
  }
}

}  // namespace

SealSummary applySealRules(SweepResults& results, const EvaluatorKey& key) {
  SealSummary sum;
  sum.key_id = key.id;
  std::set<std::string> other_ids;
  for (ReportRun& run : results.runs) {
    if (run.status != "complete" || !run.record) continue;
    const fs::path csv = results.dir / "runs" / run.id / "coverage.csv";
    std::string text;
    try {
      text = readInputFile(csv);
    } catch (const InputFileError&) {
      // loadSweepResults read it a moment ago: a vanished file is a changed record.
    }
    const SealCheck check = checkRecordSeal(key, run.metrics, text);
    if (check == SealCheck::kEvaluated) {
      ++sum.evaluated;
      continue;
    }
    if (check == SealCheck::kTampered) {
      // Sealed under this key and changed since, or re-sealed by someone without it: not a result.
      ++sum.tampered;
      run.status = "failed";
      run.failure.emplace();
      run.failure->problem =
          "key 'record_seal': the record or its coverage.csv changed after msbench sealed them "
          "under evaluator key " +
          key.id + " (tampered or re-sealed): the run is not counted";
      run.record.reset();
      continue;
    }
    if (check == SealCheck::kOtherKey) other_ids.insert(sealKeyId(run.metrics));
    ++sum.not_evaluated;
    run.unranked = notEvaluatedReason(check, run.metrics);
    run.status = "unranked";
    run.record.reset();
  }
  // Keyed records, none under this key: the evaluator gave the wrong key file.
  if (sum.evaluated == 0 && sum.tampered == 0 && !other_ids.empty())
    throw std::runtime_error("--key " + key.file + ": its key " + key.id + " sealed none of these runs; " +
                             std::to_string(other_ids.size()) + " other key(s) did (" + *other_ids.begin() +
                             (other_ids.size() > 1 ? ", ..." : "") + "): the wrong key file?");
  results.sealed_under = key.id;
  return sum;
}

}  // namespace msb
