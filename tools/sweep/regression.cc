#include "tools/sweep/regression.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/common/config_check.h"
#include "tools/results/input_files.h"
#include "tools/results/output_files.h"
#include "tools/results/run_record.h"

namespace msb {

namespace {

std::string f0(double v) {
  char b[48];
  std::snprintf(b, sizeof(b), "%.1f", v);
  return b;
}

}  // namespace

RegressionTolerance toleranceOf(const nlohmann::json& golden) {
  RegressionTolerance t;
  if (golden.contains("tolerance") && golden["tolerance"].is_object()) {
    t.relative = golden["tolerance"].value("relative", t.relative);
    t.absolute_m2 = golden["tolerance"].value("absolute_m2", t.absolute_m2);
  }
  return t;
}

nlohmann::json goldenFromSweep(const SweepResults& results, const RegressionTolerance& tolerance) {
  std::string missing;
  nlohmann::json runs = nlohmann::json::array();
  nlohmann::json machine;
  for (const ReportRun& r : results.runs) {
    if (!r.record) {
      missing += (missing.empty() ? "" : ", ") + r.id + " (" + r.status + ")";
      continue;
    }
    if (machine.is_null() && r.metrics.contains("machine")) machine = r.metrics["machine"];
    runs.push_back({{"id", r.id},
                    {"status", runStatusName(r.record->status)},
                    {"area_m2", r.record->area_m2},
                    {"sim_time_s", r.record->sim_time_s},
                    {"determinism_hash", r.record->determinism_hash},
                    {"machine_id", r.record->machine_id}});
    if (r.record->earned_m3) runs.back()["score_earned_m3"] = *r.record->earned_m3;
  }
  if (!missing.empty()) throw std::runtime_error("not every run is complete: " + missing);
  return {{"kind", kGoldenKind},
          {"machine", machine},
          {"tolerance", {{"relative", tolerance.relative}, {"absolute_m2", tolerance.absolute_m2}}},
          {"runs", runs}};
}

namespace {

std::string shortNumber(double v) {
  char b[32];
  std::snprintf(b, sizeof(b), "%g", v);
  return b;
}

// A golden's number in [lo, hi], else a FileConfigError naming the key.
void checkGoldenRange(const std::filesystem::path& file, const std::string& key, const nlohmann::json& v, double lo,
                      double hi) {
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
    throw FileConfigError(file.string() + ": key '" + key + "': expected a number in [" + shortNumber(lo) + ", " +
                          shortNumber(hi) + "]");
}

bool isHex16(const std::string& s) {
  return s.size() == 16 && std::all_of(s.begin(), s.end(), [](char c) { return std::isxdigit((unsigned char)c); });
}

}  // namespace

nlohmann::json readGolden(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw FileConfigError(file.string() + ": no such golden file");
  const nlohmann::json g = readJsonFile(file);
  if (!g.is_object()) throw FileConfigError(file.string() + ": not a JSON object");
  if (!g.contains("runs") || !g["runs"].is_array())
    throw FileConfigError(file.string() + ": key 'runs': expected a list");
  for (size_t i = 0; i < g["runs"].size(); ++i) {
    const auto& r = g["runs"][i];
    const std::string key = "runs[" + std::to_string(i) + "]";
    if (!r.is_object()) throw FileConfigError(file.string() + ": key '" + key + "': expected an object");
    for (const char* k : {"id", "status", "determinism_hash", "machine_id"})
      if (!r.contains(k) || !r[k].is_string())
        throw FileConfigError(file.string() + ": key '" + key + "." + k +
                              "': " + (r.contains(k) ? "expected a string" : "missing"));
    if (!r.contains("area_m2") || !r["area_m2"].is_number())
      throw FileConfigError(file.string() + ": key '" + key +
                            ".area_m2': " + (r.contains("area_m2") ? "expected a number" : "missing"));
    checkGoldenRange(file, key + ".area_m2", r["area_m2"], 0.0, kMaxAreaM2);
    if (r.contains("score_earned_m3"))
      checkGoldenRange(file, key + ".score_earned_m3", r["score_earned_m3"], -1e7, 1e7);
    if (!isHex16(r["determinism_hash"].get<std::string>()))
      throw FileConfigError(file.string() + ": key '" + key + ".determinism_hash': expected 16 hexadecimal digits");
  }
  if (g.contains("tolerance")) {
    const auto& t = g["tolerance"];
    if (!t.is_object()) throw FileConfigError(file.string() + ": key 'tolerance': expected an object");
    if (t.contains("relative")) checkGoldenRange(file, "tolerance.relative", t["relative"], 0.0, 1.0);
    if (t.contains("absolute_m2")) checkGoldenRange(file, "tolerance.absolute_m2", t["absolute_m2"], 0.0, 1e5);
  }
  return g;
}

bool isGoldenFile(const std::filesystem::path& file) {
  nlohmann::json g;
  try {
    g = readJsonFile(file);
  } catch (const InputFileError&) {
    return false;
  }
  if (!g.is_object()) return false;
  if (g.contains("kind")) return g["kind"] == kGoldenKind;
  // Written before "kind": exactly the keys a golden has.
  for (const auto& [k, v] : g.items())
    if (k != "machine" && k != "tolerance" && k != "runs") return false;
  return g.contains("runs") && g["runs"].is_array();
}

namespace {
// The earned score against the golden's, when the golden has one: exactly in exact mode, else
// within the relative band (at least kEarnedBandM3).
constexpr double kEarnedBandM3 = 250.0;
void compareEarned(const ReportRun& run, const nlohmann::json& g, bool exact, const RegressionTolerance& tolerance,
                   RegressionOutcome& out) {
  if (!g.contains("score_earned_m3")) return;
  const double golden = g["score_earned_m3"].get<double>();
  const auto earned = run.record->earned_m3;
  if (!earned) {
    out.regressions.push_back(run.id + ": no earned score (golden " + f0(golden) + " m³)");
    return;
  }
  const double band = exact ? 0.0 : std::max(tolerance.relative * std::fabs(golden), kEarnedBandM3);
  if (std::fabs(*earned - golden) > band)
    out.regressions.push_back(run.id + ": earned " + f0(*earned) + " m³, golden " + f0(golden) + " m³" +
                              (exact ? " (exact mode)" : " ± " + f0(band) + " (band mode)"));
}
}  // namespace

RegressionOutcome compareWithGolden(const SweepResults& results, const nlohmann::json& golden,
                                    const RegressionTolerance& tolerance) {
  RegressionOutcome out;
  if (!golden.contains("runs") || !golden["runs"].is_array()) {
    out.regressions.push_back("the golden file has no runs");
    return out;
  }
  for (const auto& g : golden["runs"]) {
    const std::string id = g.value("id", std::string());
    const auto it =
        std::find_if(results.runs.begin(), results.runs.end(), [&](const ReportRun& r) { return r.id == id; });
    if (it == results.runs.end()) {
      out.regressions.push_back(id + ": missing from the sweep");
      continue;
    }
    if (!it->record) {
      const std::string why = it->failure && !it->failure->problem.empty() ? ": " + it->failure->problem : "";
      out.regressions.push_back(id + ": did not complete (" + it->status + why + ")");
      continue;
    }
    ++out.compared;
    const MissionRecord& m = *it->record;
    const std::string status = runStatusName(m.status), g_status = g.value("status", std::string());
    const double area = m.area_m2, g_area = g.value("area_m2", 0.0);
    const std::string g_hash = g.value("determinism_hash", std::string()),
                      g_machine = g.value("machine_id", std::string());
    if (status != g_status) out.regressions.push_back(id + ": status " + status + ", golden " + g_status);
    if (!tolerance.band_only && (g_hash.empty() || g_machine.empty() || m.machine_id.empty())) {
      // Without a hash and a machine id the exact mode cannot be chosen: never fall back silently.
      out.regressions.push_back(id + ": " +
                                std::string(g_hash.empty() || g_machine.empty() ? "the golden entry" : "the run") +
                                " has no determinism hash or machine id (use --band to compare areas only)");
      continue;
    }
    const bool same_machine = m.machine_id == g_machine, same_run = m.determinism_hash == g_hash;
    if (!tolerance.band_only && (same_machine || same_run)) {
      // Same machine (same build inputs), or the very same run elsewhere: bit for bit.
      ++out.exact;
      if (area != g_area)
        out.regressions.push_back(id + ": A " + f0(area) + " m², golden " + f0(g_area) + " m² (exact mode)");
      if (!same_run)
        out.regressions.push_back(id + ": determinism hash " + m.determinism_hash + ", golden " + g_hash +
                                  " (exact mode)");
    } else {
      ++out.banded;
      const double band = std::max(tolerance.relative * g_area, tolerance.absolute_m2);
      if (std::fabs(area - g_area) > band)
        out.regressions.push_back(id + ": A " + f0(area) + " m², golden " + f0(g_area) + " m² ± " + f0(band) +
                                  " (band mode: " + (tolerance.band_only ? "asked for" : "another machine") + ")");
    }
    compareEarned(*it, g, !tolerance.band_only && (same_machine || same_run), tolerance, out);
  }
  for (const ReportRun& r : results.runs) {
    const bool known = std::any_of(golden["runs"].begin(), golden["runs"].end(),
                                   [&](const nlohmann::json& g) { return g.value("id", std::string()) == r.id; });
    if (!known) out.notes.push_back(r.id + ": not in the golden (not compared)");
  }
  return out;
}

}  // namespace msb
