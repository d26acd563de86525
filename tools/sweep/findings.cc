#include "tools/sweep/findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace msb {

const std::vector<Finding>& findingsTable() {
  using C = FindingCheck;
  static const std::vector<Finding> table = {
      {"ms_vs_grid_urban",
       "MonoSpheres covers at least twice the grid baseline's mean A in urban",
       C::kRatioAtLeast,
       "urban",
       {"monospheres", "grid_random"},
       {},
       2.0,
       ""},
      {"ms_vs_grid_cave",
       "MonoSpheres covers at least twice the grid baseline's mean A in the cave",
       C::kRatioAtLeast,
       "cave",
       {"monospheres", "grid_random"},
       {},
       2.0,
       ""},
      {"ms_vs_grid_rooftops",
       "MonoSpheres covers at least twice the grid baseline's mean A on the rooftops",
       C::kRatioAtLeast,
       "rooftops",
       {"monospheres", "grid_random"},
       {},
       2.0,
       ""},
      {"ms_vs_grid_sparse",
       "MonoSpheres covers at least twice the grid baseline's mean A in the sparse world",
       C::kRatioAtLeast,
       "sparse",
       {"monospheres", "grid_random"},
       {},
       2.0,
       ""},
      {"no_ovde_urban",
       "without OVDE MonoSpheres covers at most 0.3x its full mean A in urban",
       C::kRatioAtMost,
       "urban",
       {"monospheres -ovde", "monospheres"},
       {},
       0.3,
       ""},
      {"ablation_order_urban",
       "urban ablation order: full > no VPB > no FFF ≈ no DBOF > no OVDE (≈: within 25 %)",
       C::kOrder,
       "urban",
       {"monospheres", "monospheres -vpb", "monospheres -fff", "monospheres -dbof", "monospheres -ovde"},
       {">", ">", "≈", ">"},
       0.25,
       ""},
      {"cave_no_collision",
       "no collision in the cave for either method",
       C::kNoCollisions,
       "cave",
       {"monospheres", "grid_random"},
       {},
       0.0,
       ""},
      {"urban_collision_kinds",
       "urban collisions only on textureless or thin objects",
       C::kCollisionKinds,
       "urban",
       {},
       {},
       0.0,
       "grid: a smooth metal rod; MonoSpheres: a car, a burned wall"},
      {"urban_collisions_late",
       "MonoSpheres' urban collisions come after the majority of the box",
       C::kCollisionsLate,
       "urban",
       {"monospheres"},
       {},
       0.5,
       "\"after exploring the majority of the environment\""},
  };
  return table;
}

namespace {

using stats::Estimate;
using stats::Verdict;

std::string number(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f", digits, v);
  return b;
}

// "1 collision", "2 collisions".
std::string counted(int n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

// "1.85 [1.58, 2.37]".
std::string withInterval(const Estimate& e, int digits = 2) {
  return number(e.value, digits) + " [" + number(e.ci.lo, digits) + ", " + number(e.ci.hi, digits) + "]";
}

// The row of `method` ("monospheres -dbof"), whatever published-code switches it runs with
// ("+published": a table made under the published code answers the same findings).
const ReportRow* findRow(const std::vector<ReportRow>& rows, const std::string& world, const std::string& method) {
  auto base = [](const std::string& name) {
    std::istringstream words(name);
    std::string out, w;
    while (words >> w)
      if (w[0] != '+') out += (out.empty() ? "" : " ") + w;
    return out;
  };
  for (const ReportRow& r : rows)
    if (r.world == world && base(r.method) == method && r.area_m2.count > 0) return &r;
  return nullptr;
}

void setVerdict(FindingResult& out, Verdict v) { out.status = stats::verdictName(v); }

// A row of one run has no spread to resample: its interval would be a point, so no verdict.
bool hasInterval(const ReportRow& a, const ReportRow& b) { return a.area_m2.count >= 2 && b.area_m2.count >= 2; }
const std::string kOneRun = "a row of one run has no interval: undecided whatever the ratio";

// The paired ratio on common seeds and the saturation of either row, in words.
std::string ratioNote(const ReportRow& a, const ReportRow& b) {
  std::string note;
  const PairedAreas p = pairedAreas(a, b);
  if (p.a.size() >= 2 && stats::mean(p.b) > 0) {
    const auto rho = stats::correlation(p.a, p.b);
    note = "paired on " + std::to_string(p.a.size()) +
           " common seeds: " + withInterval(stats::bootstrapPairedRatio(p.a, p.b)) +
           (rho ? ", r = " + number(*rho, 2) : "");
  }
  bool saturated = false;
  for (const ReportRow* r : {&a, &b})
    if (isSaturated(*r)) {
      saturated = true;
      note += std::string(note.empty() ? "" : "; ") + r->method + " fills the box in " + std::to_string(r->saturated) +
              " of " + std::to_string(r->complete) + " runs: its A is bounded by the box";
    }
  if (saturated && a.t50_s.count > 0 && b.t50_s.count > 0 && a.t50_s.mean > 0 && b.t50_s.mean > 0) {
    // Time to half the box, the second row's over the first's (over the runs that got there; when
    // some runs never did, the true ratio of the slower row is larger: a lower bound).
    const bool censored = a.t50_s.count < a.complete || b.t50_s.count < b.complete;
    note += "; t50 " + b.method + " / " + a.method + " = " +
            withInterval(stats::bootstrapRatio(b.t50_s.values, a.t50_s.values)) + " (" + std::to_string(b.t50_s.count) +
            " of " + std::to_string(b.complete) + " and " + std::to_string(a.t50_s.count) + " of " +
            std::to_string(a.complete) + " runs reached 50 %" + (censored ? "; the rest never did" : "") + ")";
  }
  return note;
}

void evaluateRatio(const Finding& f, const std::vector<ReportRow>& rows, FindingResult& out) {
  const ReportRow* a = findRow(rows, f.world, f.methods[0]);
  const ReportRow* b = findRow(rows, f.world, f.methods[1]);
  if (!a || !b || b->area_m2.mean <= 0) return;
  const Estimate e = stats::bootstrapRatio(a->area_m2.values, b->area_m2.values);
  const auto side = f.check == FindingCheck::kRatioAtLeast ? stats::Side::kAtLeast : stats::Side::kAtMost;
  const Verdict v = hasInterval(*a, *b) ? stats::verdictOf(e.ci, f.threshold, side) : Verdict::kUndecided;
  setVerdict(out, v);
  out.estimate = e;
  out.runs = a->area_m2.count + b->area_m2.count;
  out.measured = number(a->area_m2.mean, 0) + " / " + number(b->area_m2.mean, 0) + " = " + withInterval(e) + " (" +
                 std::to_string(a->area_m2.count) + " and " + counted(b->area_m2.count, "run") + ")";
  if (v == Verdict::kUndecided && hasInterval(*a, *b))
    out.seeds_to_decide = stats::seedsToDecide(e, f.threshold, a->area_m2.count, b->area_m2.count);
  out.note = ratioNote(*a, *b);
  if (!hasInterval(*a, *b)) out.note = kOneRun + (out.note.empty() ? "" : "; " + out.note);
}

// One link of an order: "A_{i-1} > A_i" (ratio above 1) or "≈" (ratio within the relative band).
Verdict linkVerdict(const Estimate& e, const std::string& relation, double band, double& nearest_edge) {
  if (relation == ">") {
    nearest_edge = 1.0;
    return stats::verdictOf(e.ci, 1.0, stats::Side::kAtLeast);
  }
  const double lo = 1.0 - band, hi = 1.0 / (1.0 - band);  // |x - y| <= band * max(x, y)
  nearest_edge = std::abs(e.value - lo) < std::abs(e.value - hi) ? lo : hi;
  if (e.ci.lo >= lo && e.ci.hi <= hi) return Verdict::kHolds;
  if (e.ci.hi < lo || e.ci.lo > hi) return Verdict::kFails;
  return Verdict::kUndecided;
}

void evaluateOrder(const Finding& f, const std::vector<ReportRow>& rows, FindingResult& out) {
  std::vector<const ReportRow*> chain;
  for (const auto& m : f.methods) chain.push_back(findRow(rows, f.world, m));
  for (const ReportRow* r : chain)
    if (!r || !(r->area_m2.mean > 0)) return;
  bool any_fails = false, all_hold = true;
  std::string links;
  for (size_t i = 0; i < chain.size(); ++i) {
    if (i > 0) out.measured += " " + f.relations[i - 1] + " ";
    out.measured += number(chain[i]->area_m2.mean, 0);
    out.runs += chain[i]->area_m2.count;
    if (i == 0) continue;
    const Estimate e = stats::bootstrapRatio(chain[i - 1]->area_m2.values, chain[i]->area_m2.values);
    double edge = 1.0;
    Verdict v = linkVerdict(e, f.relations[i - 1], f.threshold, edge);
    const bool spread = hasInterval(*chain[i - 1], *chain[i]);
    if (!spread) v = Verdict::kUndecided, out.note = kOneRun;
    any_fails = any_fails || v == Verdict::kFails;
    all_hold = all_hold && v == Verdict::kHolds;
    if (v == Verdict::kUndecided && spread) {
      const auto n = stats::seedsToDecide(e, edge, chain[i - 1]->area_m2.count, chain[i]->area_m2.count);
      if (n && (!out.seeds_to_decide || *n > *out.seeds_to_decide)) out.seeds_to_decide = n;
    }
    links += std::string(links.empty() ? "" : ", ") + withInterval(e) + " " + stats::verdictName(v);
  }
  out.measured += " (neighbour ratios: " + links + ")";
  setVerdict(out, any_fails ? Verdict::kFails : all_hold ? Verdict::kHolds : Verdict::kUndecided);
  if (any_fails) out.seeds_to_decide.reset();
}

// A claim that an event never happens (k of n): holds at k = 0; fails when the exact test
// separates k of n from the paper's k0 of n0 (p < 0.05); undecided otherwise.
void rateVerdict(FindingResult& out, int k, int n, int k0, int n0, const std::string& events, const std::string& of) {
  out.runs = n;
  if (n > 0) {
    out.estimate = Estimate{static_cast<double>(k) / n, stats::wilson(k, n), n};
    out.measured += " (rate " + withInterval(*out.estimate) + ")";
  }
  if (n0 > 0) out.p_value = stats::fisherExact(k, n, k0, n0);
  out.paper = std::to_string(k0) + " " + events + " in " + counted(n0, of);
  if (k == 0) return setVerdict(out, Verdict::kHolds);
  if (out.p_value) out.measured += ", exact test against the paper's p = " + number(*out.p_value, 3);
  setVerdict(out, out.p_value && *out.p_value < 0.05 ? Verdict::kFails : Verdict::kUndecided);
}

// The paper's collisions in `world` over the rows of `methods` (all when empty); -1: not given.
std::pair<int, int> paperCollisions(const std::vector<ReportRow>& rows, const std::string& world,
                                    const std::vector<std::string>& methods) {
  int k = 0, n = 0;
  for (const ReportRow& r : rows) {
    if (r.world != world || r.area_m2.count == 0) continue;
    if (!methods.empty() && std::find(methods.begin(), methods.end(), r.method) == methods.end()) continue;
    if (r.paper_runs > 0 && r.paper_collisions >= 0) k += r.paper_collisions, n += r.paper_runs;
  }
  return {k, n};
}

void evaluateNoCollisions(const Finding& f, const std::vector<ReportRow>& rows, FindingResult& out) {
  int crashes = 0, runs = 0;
  for (const auto& m : f.methods)
    if (const ReportRow* r = findRow(rows, f.world, m)) crashes += r->crashes, runs += r->complete;
  if (runs == 0) return;
  out.measured = counted(crashes, "collision") + " in " + counted(runs, "run");
  const auto [k0, n0] = paperCollisions(rows, f.world, f.methods);
  rateVerdict(out, crashes, runs, k0, n0, "collisions", "run");
}

void evaluateCollisionKinds(const Finding& f, const std::vector<ReportRow>& rows, FindingResult& out) {
  int crashes = 0, other = 0, runs = 0;
  for (const ReportRow& r : rows) {
    if (r.world != f.world) continue;
    runs += r.complete;
    crashes += r.crashes;
    for (const auto& [kind, n] : r.collisions_by_kind)
      if (kind != "textureless" && kind != "thin") other += n;
  }
  if (runs == 0) return;
  out.measured = counted(crashes, "collision") + " in " + counted(runs, "run") + ", " + std::to_string(other) +
                 " on other objects";
  const int paper_crashes = paperCollisions(rows, f.world, {}).first;
  rateVerdict(out, other, crashes, 0, paper_crashes, "on other objects", "collision");
}

void evaluateCollisionsLate(const Finding& f, const SweepResults& results, const std::vector<ReportRow>& rows,
                            FindingResult& out) {
  int crashes = 0, early = 0, runs = 0;
  std::string shares;
  for (const ReportRun& run : results.runs) {
    const nlohmann::json& m = run.metrics;
    if (!run.record || run.record->world != f.world) continue;
    // The method as named with its switches, the published code's label ("+published") aside:
    // the finding is about the method under either code.
    const std::string name = reportMethodName(m);
    if (std::find(f.methods.begin(), f.methods.end(), name.substr(0, name.find(" +"))) == f.methods.end()) continue;
    ++runs;
    if (run.record->status != RunStatus::kCollided) continue;
    ++crashes;
    const double share = run.record->box_share.value_or(0.0);
    early += share < f.threshold;
    shares += (shares.empty() ? "" : ", ") + number(share, 2);
  }
  if (runs == 0) return;
  out.measured = counted(crashes, "collision") + " in " + counted(runs, "run") +
                 (shares.empty() ? "" : ", box share at contact " + shares) + "; " + std::to_string(early) + " early";
  const int paper_crashes = paperCollisions(rows, f.world, f.methods).first;
  rateVerdict(out, early, crashes, 0, paper_crashes, "early", "collision");
}

// The paper's figures of a ratio or order finding, from the method registry.
std::string paperFigures(const Finding& f) {
  const bool ratio = f.check == FindingCheck::kRatioAtLeast || f.check == FindingCheck::kRatioAtMost;
  if (!ratio && f.check != FindingCheck::kOrder) return "";
  std::vector<const PaperRow*> paper;
  for (const auto& m : f.methods) paper.push_back(paperRowNamed(f.world, m));
  for (const PaperRow* p : paper)
    if (!p) return "";
  std::string s;
  if (f.check == FindingCheck::kOrder) {
    for (size_t i = 0; i < paper.size(); ++i)
      s += (i ? " " + f.relations[i - 1] + " " : "") + number(paper[i]->mean_area_m2, 0);
    return s;
  }
  return number(paper[0]->mean_area_m2, 0) + " / " + number(paper[1]->mean_area_m2, 0) + " = " +
         number(paper[0]->mean_area_m2 / paper[1]->mean_area_m2, 2) + " (" + std::to_string(paper[0]->runs) + " and " +
         counted(paper[1]->runs, "run") + ")";
}

FindingResult evaluate(const Finding& f, const SweepResults& results, const std::vector<ReportRow>& rows) {
  FindingResult out;
  out.finding = &f;
  switch (f.check) {
    case FindingCheck::kRatioAtLeast:
    case FindingCheck::kRatioAtMost:
      evaluateRatio(f, rows, out);
      break;
    case FindingCheck::kOrder:
      evaluateOrder(f, rows, out);
      break;
    case FindingCheck::kNoCollisions:
      evaluateNoCollisions(f, rows, out);
      break;
    case FindingCheck::kCollisionKinds:
      evaluateCollisionKinds(f, rows, out);
      break;
    case FindingCheck::kCollisionsLate:
      evaluateCollisionsLate(f, results, rows, out);
      break;
  }
  if (out.paper.empty()) out.paper = paperFigures(f);
  if (*f.paper_note) out.paper += std::string(out.paper.empty() ? "" : ": ") + f.paper_note;
  if (out.status.empty()) {
    out.status = "n/a";
    out.measured = "the sweep has no runs of these rows";
    out.estimate.reset(), out.p_value.reset(), out.seeds_to_decide.reset();
  }
  return out;
}

const char* mark(const std::string& status) {
  return status == "holds" ? "✓" : status == "fails" ? "✗" : status == "undecided" ? "?" : "–";
}

std::string csvField(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The rows with verified A in place of the paper's A; none unless some row has it, and a row
// whose runs do not all have it has no A (its findings are n/a).
std::optional<std::vector<ReportRow>> onVerifiedArea(const std::vector<ReportRow>& rows) {
  std::vector<ReportRow> out = rows;
  bool any = false;
  for (ReportRow& r : out) {
    const bool all = r.verified_area_m2.count > 0 && r.verified_area_m2.count == r.area_m2.count;
    any = any || all;
    r.area_m2 = all ? r.verified_area_m2 : MeanOf{};
  }
  if (!any) return std::nullopt;
  return out;
}

// True if some finding was evaluated on verified A (not only "n/a").
bool hasVerified(const std::vector<FindingResult>& findings) {
  return std::any_of(findings.begin(), findings.end(),
                     [](const FindingResult& r) { return !r.verified_status.empty() && r.verified_status != "n/a"; });
}

bool isAreaFinding(const Finding& f) {
  return f.check == FindingCheck::kRatioAtLeast || f.check == FindingCheck::kRatioAtMost ||
         f.check == FindingCheck::kOrder;
}

}  // namespace

std::vector<FindingResult> evaluateFindings(const SweepResults& results, const std::vector<ReportRow>& rows,
                                            const std::vector<Finding>& table) {
  std::vector<FindingResult> out;
  const bool table_one = isTableOneSweep(results);
  for (const Finding& f : table) {
    if (table_one) {
      out.push_back(evaluate(f, results, rows));
      continue;
    }
    // The paper's findings are claims about its 20-minute Table I runs: elsewhere nothing to decide.
    FindingResult r;
    r.finding = &f;
    r.status = "n/a";
    r.measured = "—";
    r.note = "not a Table I sweep (docs/sweeps.md, \"Reports\")";
    out.push_back(r);
  }
  // The area findings once more on verified A (comparability stays with the paper's A).
  const auto verified = table_one ? onVerifiedArea(rows) : std::nullopt;
  for (size_t i = 0; verified && i < out.size(); ++i) {
    if (!isAreaFinding(table[i])) continue;
    const FindingResult v = evaluate(table[i], results, *verified);
    out[i].verified_status = v.status;
    out[i].verified_measured = v.measured;
  }
  return out;
}

FindingCounts countFindings(const std::vector<FindingResult>& findings) {
  FindingCounts c;
  for (const auto& r : findings)
    (r.status == "holds"       ? c.holds
     : r.status == "fails"     ? c.fails
     : r.status == "undecided" ? c.undecided
                               : c.not_evaluated)++;
  return c;
}

std::string findingsMarkdown(const std::vector<FindingResult>& findings) {
  const FindingCounts c = countFindings(findings);
  std::ostringstream o;
  // A sweep where none applies (not a Table I sweep): one sentence, not a table of n/a rows.
  if (!findings.empty() && c.not_evaluated == int(findings.size()) &&
      std::all_of(findings.begin(), findings.end(), [](const FindingResult& r) { return r.status == "n/a"; })) {
    o << "\n## Findings\n\nThe paper's " << findings.size()
      << " findings are claims about its Table I runs (20 simulated minutes in its worlds); none applies to this "
         "sweep (docs/sweeps.md, \"Reports\"); findings.csv lists them as n/a.\n";
    return o.str();
  }
  o << "\n## Findings\n\nThe paper's qualitative findings as checks (tools/sweep/findings.cc): " << c.holds
    << " hold (✓), " << c.fails << " fail (✗), " << c.undecided << " undecided (?), " << c.not_evaluated
    << " not evaluated. A ratio holds when its 95 % bootstrap interval lies on the paper's side of the threshold, "
       "fails when it lies on the other side, and is undecided when it straddles it (with the seeds per row that would "
       "decide it at the observed spread); a claim that an event never happens holds when none happened, fails when "
       "Fisher's exact test separates the count from the paper's (p < 0.05), and is undecided otherwise "
       "(docs/sweeps.md, \"Intervals and verdicts\").\n\n";
  // With verified coverage: the area findings on verified A beside (the verdicts above are on the
  // paper's A, for comparability).
  const bool verified = hasVerified(findings);
  if (verified)
    o << "The column \"on verified A\" repeats each area finding with verified A (docs/metrics.md) in place of "
         "the paper's A: \"same\" when the verdict agrees.\n\n";
  o << "| | finding | measured [95 % CI] | paper | seeds per row to decide | note |"
    << (verified ? " on verified A |" : "") << "\n| --- | --- | --- | --- | --- | --- |" << (verified ? " --- |" : "")
    << "\n";
  for (const auto& r : findings) {
    o << "| " << mark(r.status) << " " << r.status << " | " << r.finding->claim << " | " << r.measured << " | "
      << (r.paper.empty() ? "—" : r.paper) << " | "
      << (r.seeds_to_decide ? "≈ " + std::to_string(*r.seeds_to_decide) : std::string("—")) << " | "
      << (r.note.empty() ? "—" : r.note) << " |";
    if (verified)
      o << " "
        << (r.verified_status.empty() ? std::string("—")
            : r.verified_status == r.status
                ? "same: " + r.verified_measured
                : "**" + std::string(mark(r.verified_status)) + " " + r.verified_status + "**: " + r.verified_measured)
        << " |";
    o << "\n";
  }
  return o.str();
}

std::string findingsCsv(const std::vector<FindingResult>& findings) {
  const bool verified = hasVerified(findings);
  std::string csv = "id,claim,verdict,measured,estimate,ci_lo,ci_hi,n,threshold,p_value,seeds_to_decide,paper,note" +
                    std::string(verified ? ",verified_verdict,verified_measured" : "") + "\n";
  for (const auto& r : findings) {
    const auto& e = r.estimate;
    csv += std::string(r.finding->id) + "," + csvField(r.finding->claim) + "," + r.status + "," + csvField(r.measured) +
           "," + (e ? number(e->value, 4) + "," + number(e->ci.lo, 4) + "," + number(e->ci.hi, 4) : std::string(",,")) +
           "," + std::to_string(r.runs) + "," + number(r.finding->threshold, 2) + "," +
           (r.p_value ? number(*r.p_value, 4) : "") + "," +
           (r.seeds_to_decide ? std::to_string(*r.seeds_to_decide) : "") + "," + csvField(r.paper) + "," +
           csvField(r.note) +
           (verified ? "," + r.verified_status + "," + csvField(r.verified_measured) : std::string()) + "\n";
  }
  return csv;
}

}  // namespace msb
