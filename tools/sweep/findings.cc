#include "tools/sweep/findings.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace msb {

const std::vector<Finding>& findingsTable() {
  using C = FindingCheck;
  static const std::vector<Finding> table = {
      {"ms_vs_grid_urban", "MonoSpheres covers at least twice the grid baseline's mean A in urban", C::kRatioAtLeast,
       "urban", {"monospheres", "grid_random"}, {}, 2.0, "4919 / 1911 = 2.57"},
      {"ms_vs_grid_cave", "MonoSpheres covers at least twice the grid baseline's mean A in the cave", C::kRatioAtLeast,
       "cave", {"monospheres", "grid_random"}, {}, 2.0, "7627 / 3171 = 2.41"},
      {"ms_vs_grid_rooftops", "MonoSpheres covers at least twice the grid baseline's mean A on the rooftops",
       C::kRatioAtLeast, "rooftops", {"monospheres", "grid_random"}, {}, 2.0, "3760 / 1360 = 2.76"},
      {"ms_vs_grid_sparse", "MonoSpheres covers at least twice the grid baseline's mean A in the sparse world",
       C::kRatioAtLeast, "sparse", {"monospheres", "grid_random"}, {}, 2.0, "5127 / 2108 = 2.43"},
      {"no_ovde_urban", "without OVDE MonoSpheres covers at most 0.3x its full mean A in urban", C::kRatioAtMost,
       "urban", {"monospheres -ovde", "monospheres"}, {}, 0.3, "747 / 4919 = 0.15"},
      {"ablation_order_urban", "urban ablation order: full > no VPB > no FFF ≈ no DBOF > no OVDE (≈: within 25 %)",
       C::kOrder, "urban", {"monospheres", "monospheres -vpb", "monospheres -fff", "monospheres -dbof", "monospheres -ovde"},
       {">", ">", "≈", ">"}, 0.25, "4919 > 3697 > 2470 ≈ 2308 > 747"},
      {"cave_no_collision", "no collision in the cave for either method", C::kNoCollisions, "cave",
       {"monospheres", "grid_random"}, {}, 0.0, "0 of 3 runs each"},
      {"urban_collision_kinds", "urban collisions only on textureless or thin objects", C::kCollisionKinds, "urban", {},
       {}, 0.0, "grid: a smooth metal rod; MonoSpheres: a car, a burned wall"},
      {"urban_collisions_late", "MonoSpheres' urban collisions come after the majority of the box", C::kCollisionsLate,
       "urban", {"monospheres"}, {}, 0.5, "2 of 6 runs, \"after exploring the majority of the environment\""},
  };
  return table;
}

namespace {

std::string number(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f", digits, v);
  return b;
}

// "1 collision", "2 collisions".
std::string counted(int n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

const ReportRow* findRow(const std::vector<ReportRow>& rows, const std::string& world, const std::string& method) {
  for (const ReportRow& r : rows)
    if (r.world == world && r.method == method && r.area_m2.count > 0) return &r;
  return nullptr;
}

FindingResult evaluate(const Finding& f, const SweepResults& results, const std::vector<ReportRow>& rows) {
  FindingResult out;
  out.finding = &f;
  auto verdict = [&](bool ok) { out.status = ok ? "pass" : "fail"; };
  switch (f.check) {
    case FindingCheck::kRatioAtLeast:
    case FindingCheck::kRatioAtMost: {
      const ReportRow* a = findRow(rows, f.world, f.methods[0]);
      const ReportRow* b = findRow(rows, f.world, f.methods[1]);
      if (!a || !b || b->area_m2.mean <= 0) break;
      const double ratio = a->area_m2.mean / b->area_m2.mean;
      out.measured = number(a->area_m2.mean, 0) + " / " + number(b->area_m2.mean, 0) + " = " + number(ratio, 2) +
                     " (" + std::to_string(a->area_m2.count) + " and " + counted(b->area_m2.count, "run") + ")";
      verdict(f.check == FindingCheck::kRatioAtLeast ? ratio >= f.threshold : ratio <= f.threshold);
      break;
    }
    case FindingCheck::kOrder: {
      std::vector<const ReportRow*> chain;
      for (const auto& m : f.methods) chain.push_back(findRow(rows, f.world, m));
      bool all = true;
      for (const ReportRow* r : chain) all = all && r;
      if (!all) break;
      bool ok = true;
      for (size_t i = 0; i < chain.size(); ++i) {
        if (i > 0) out.measured += " " + f.relations[i - 1] + " ";
        out.measured += number(chain[i]->area_m2.mean, 0);
        if (i == 0) continue;
        const double hi = chain[i - 1]->area_m2.mean, lo = chain[i]->area_m2.mean;
        if (f.relations[i - 1] == ">") ok = ok && hi > lo;
        else ok = ok && std::abs(hi - lo) <= f.threshold * std::max(hi, lo);
      }
      verdict(ok);
      break;
    }
    case FindingCheck::kNoCollisions: {
      int crashes = 0, runs = 0;
      for (const auto& m : f.methods)
        if (const ReportRow* r = findRow(rows, f.world, m)) crashes += r->crashes, runs += r->complete;
      if (runs == 0) break;
      out.measured = counted(crashes, "collision") + " in " + counted(runs, "run");
      verdict(crashes == 0);
      break;
    }
    case FindingCheck::kCollisionKinds: {
      int crashes = 0, other = 0, runs = 0;
      for (const ReportRow& r : rows) {
        if (r.world != f.world) continue;
        runs += r.complete;
        crashes += r.crashes;
        for (const auto& [kind, n] : r.collisions_by_kind)
          if (kind != "textureless" && kind != "thin") other += n;
      }
      if (runs == 0) break;
      out.measured = counted(crashes, "collision") + " in " + counted(runs, "run") + ", " +
                     std::to_string(other) + " on other objects";
      verdict(other == 0);
      break;
    }
    case FindingCheck::kCollisionsLate: {
      int crashes = 0, early = 0, runs = 0;
      std::string shares;
      for (const ReportRun& run : results.runs) {
        const nlohmann::json& m = run.metrics;
        if (run.status != "complete" || !m.is_object() || m.value("world", std::string()) != f.world) continue;
        bool ours = false;
        for (const auto& name : f.methods) ours = ours || reportMethodName(m) == name;
        if (!ours) continue;
        ++runs;
        if (m.value("status", std::string()) != "collided") continue;
        ++crashes;
        const auto& cov = m["coverage"];
        const double share = cov.is_object() && cov.contains("box_share") && cov["box_share"].is_number()
                                 ? cov["box_share"].get<double>() : 0.0;
        early += share < f.threshold;
        shares += (shares.empty() ? "" : ", ") + number(share, 2);
      }
      if (runs == 0) break;
      out.measured = counted(crashes, "collision") + " in " + counted(runs, "run") +
                     (shares.empty() ? "" : ", box share at contact " + shares);
      verdict(early == 0);
      break;
    }
  }
  if (out.status.empty()) {
    out.status = "n/a";
    out.measured = "the sweep has no runs of these rows";
  }
  return out;
}

const char* mark(const std::string& status) { return status == "pass" ? "✓" : status == "fail" ? "✗" : "–"; }

std::string csvField(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::vector<FindingResult> evaluateFindings(const SweepResults& results, const std::vector<ReportRow>& rows,
                                            const std::vector<Finding>& table) {
  std::vector<FindingResult> out;
  for (const Finding& f : table) out.push_back(evaluate(f, results, rows));
  return out;
}

std::string findingsMarkdown(const std::vector<FindingResult>& findings) {
  int pass = 0, fail = 0;
  for (const auto& r : findings) pass += r.status == "pass", fail += r.status == "fail";
  std::ostringstream o;
  o << "\n## Findings\n\nThe paper's qualitative findings as checks (tools/sweep/findings.cc): " << pass << " ✓, "
    << fail << " ✗, " << findings.size() - pass - fail << " not evaluated.\n\n"
    << "| | finding | measured | paper |\n| --- | --- | --- | --- |\n";
  for (const auto& r : findings)
    o << "| " << mark(r.status) << " | " << r.finding->claim << " | " << r.measured << " | " << r.finding->paper << " |\n";
  return o.str();
}

std::string findingsCsv(const std::vector<FindingResult>& findings) {
  std::string csv = "id,claim,status,measured,threshold,paper\n";
  for (const auto& r : findings)
    csv += std::string(r.finding->id) + "," + csvField(r.finding->claim) + "," + r.status + "," + csvField(r.measured) +
           "," + number(r.finding->threshold, 2) + "," + csvField(r.finding->paper) + "\n";
  return csv;
}

}  // namespace msb
