#include "tools/sweep/suite.h"

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "tools/config/scenario_yaml.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// (world, fixed-settings hash) of the scenario in a run's config.yaml.
std::pair<std::string, std::string> settingsOf(const fs::path& config) {
  const ScenarioSpec spec = loadScenario(config.string());
  return {spec.flight.world_name.empty() ? spec.flight.world_path : spec.flight.world_name, spec.fixed_settings_hash};
}

}  // namespace

void applySuite(SweepResults& results, const fs::path& suite_dir) {
  // The suite: per world, the hashes its published runs flew with.
  std::map<std::string, std::set<std::string>> allowed;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(suite_dir / "runs", ec)) {
    if (!fs::is_regular_file(e.path() / "config.yaml")) continue;
    const auto [world, hash] = settingsOf(e.path() / "config.yaml");
    allowed[world].insert(hash);
  }
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
    if (!confinement.empty() && !m.contains("record_digest"))
      run.unranked = "unsealed: its record has no record_digest, which every build that records confinement writes";
    else if (confinement.find("unconfined") != std::string::npos || confinement.find("in-process") != std::string::npos)
      run.unranked = "unconfined: its method ran " + confinement;
    if (run.unranked.empty()) continue;
    run.status = "unranked";
    run.record.reset();
  }
}

std::string suiteNamedByRuns(const SweepResults& results) {
  std::set<std::string> named;
  for (const ReportRun& r : results.runs) {
    if (!r.record) continue;
    const auto it = r.metrics.find("suite");
    named.insert(it != r.metrics.end() && it->is_string() ? it->get<std::string>() : "");
  }
  named.erase("");
  if (named.size() > 1)
    throw std::runtime_error("the runs name " + std::to_string(named.size()) + " suites (" + *named.begin() + ", " +
                             *std::next(named.begin()) + ", ...): give --suite");
  return named.empty() ? "" : *named.begin();
}

}  // namespace msb
