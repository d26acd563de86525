#include "tools/sweep/regression.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace msb {

namespace {

std::string machineId(const nlohmann::json& metrics) {
  if (!metrics.is_object() || !metrics.contains("machine") || !metrics["machine"].is_object()) return "";
  return metrics["machine"].value("id", std::string());
}

double areaOf(const nlohmann::json& metrics) {
  const auto& c = metrics["coverage"];
  return c.is_object() && c.contains("area_m2") && c["area_m2"].is_number() ? c["area_m2"].get<double>() : 0.0;
}

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
    if (r.status != "complete" || !r.metrics.is_object() || r.metrics.value("status", std::string()) == "error") {
      missing += (missing.empty() ? "" : ", ") + r.id + " (" + r.status + ")";
      continue;
    }
    if (machine.is_null() && r.metrics.contains("machine")) machine = r.metrics["machine"];
    runs.push_back({{"id", r.id},
                    {"status", r.metrics.value("status", std::string())},
                    {"area_m2", areaOf(r.metrics)},
                    {"sim_time_s", r.metrics.value("sim_time_s", 0.0)},
                    {"determinism_hash", r.metrics.value("determinism_hash", std::string())},
                    {"machine_id", machineId(r.metrics)}});
  }
  if (!missing.empty()) throw std::runtime_error("not every run is complete: " + missing);
  return {{"machine", machine},
          {"tolerance", {{"relative", tolerance.relative}, {"absolute_m2", tolerance.absolute_m2}}},
          {"runs", runs}};
}

RegressionOutcome compareWithGolden(const SweepResults& results, const nlohmann::json& golden,
                                    const RegressionTolerance& tolerance) {
  RegressionOutcome out;
  if (!golden.contains("runs") || !golden["runs"].is_array()) {
    out.regressions.push_back("the golden file has no runs");
    return out;
  }
  for (const auto& g : golden["runs"]) {
    const std::string id = g.value("id", std::string());
    const auto it = std::find_if(results.runs.begin(), results.runs.end(), [&](const ReportRun& r) { return r.id == id; });
    if (it == results.runs.end()) {
      out.regressions.push_back(id + ": missing from the sweep");
      continue;
    }
    const nlohmann::json& m = it->metrics;
    if (it->status != "complete" || !m.is_object() || m.value("status", std::string()) == "error") {
      out.regressions.push_back(id + ": did not complete (" + it->status + ")");
      continue;
    }
    ++out.compared;
    const std::string status = m.value("status", std::string()), g_status = g.value("status", std::string());
    const double area = areaOf(m), g_area = g.value("area_m2", 0.0);
    const std::string hash = m.value("determinism_hash", std::string()), g_hash = g.value("determinism_hash", std::string());
    const bool same_machine = !machineId(m).empty() && machineId(m) == g.value("machine_id", std::string());
    if (status != g_status) out.regressions.push_back(id + ": status " + status + ", golden " + g_status);
    if (same_machine) {
      // Same machine, same build inputs: the run must repeat bit for bit.
      ++out.exact;
      if (area != g_area) out.regressions.push_back(id + ": A " + f0(area) + " m², golden " + f0(g_area) + " m² (exact mode)");
      if (hash != g_hash) out.regressions.push_back(id + ": determinism hash " + hash + ", golden " + g_hash + " (exact mode)");
    } else {
      ++out.banded;
      const double band = std::max(tolerance.relative * g_area, tolerance.absolute_m2);
      if (std::fabs(area - g_area) > band)
        out.regressions.push_back(id + ": A " + f0(area) + " m², golden " + f0(g_area) + " m² ± " + f0(band) +
                                  " (band mode: another machine)");
    }
  }
  for (const ReportRun& r : results.runs) {
    const bool known = std::any_of(golden["runs"].begin(), golden["runs"].end(),
                                   [&](const nlohmann::json& g) { return g.value("id", std::string()) == r.id; });
    if (!known) out.notes.push_back(r.id + ": not in the golden (not compared)");
  }
  return out;
}

}  // namespace msb
