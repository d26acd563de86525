#include "tools/sweep/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/common/strict_number.h"
#include "tools/config/method_table.h"
#include "tools/results/input_files.h"
#include "tools/results/output_files.h"
#include "tools/sweep/coverage_csv.h"
#include "tools/sweep/markdown_text.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

void add(MeanOf& m, double v) {
  m.mean = (m.mean * m.count + v) / (m.count + 1);
  ++m.count;
  m.values.push_back(v);
}

double number(const nlohmann::json& j, const char* key, double fallback = 0.0) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

std::string fixed(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof(b), "%.*f", digits, v);
  return b;
}

// "mean (k/n)" when only k of n runs have a value, "—" when none has.
std::string meanCell(const MeanOf& m, int runs, int digits, const std::string& unit = "") {
  if (m.count == 0) return "—";
  std::string s = fixed(m.mean, digits) + unit;
  if (m.count < runs) s += " (" + std::to_string(m.count) + "/" + std::to_string(runs) + ")";
  return s;
}

// "mean [lo, hi]" with its 95 % bootstrap interval, "(k/n)" when only k of n runs have a value.
// Fewer than 3 values have no interval: "mean {min, max}", their range, and a lone value alone.
std::string intervalCell(const MeanOf& m, int runs, int digits) {
  if (m.count == 0) return "—";
  std::string s;
  if (m.count < 3) {
    const auto [lo, hi] = std::minmax_element(m.values.begin(), m.values.end());
    s = fixed(m.mean, digits) + (m.count == 2 ? " {" + fixed(*lo, digits) + ", " + fixed(*hi, digits) + "}" : "");
    if (m.count < runs) s += " (" + std::to_string(m.count) + "/" + std::to_string(runs) + ")";
    return s;
  }
  const stats::Estimate e = estimateOf(m);
  s = fixed(e.value, digits) + " [" + fixed(e.ci.lo, digits) + ", " + fixed(e.ci.hi, digits) + "]";
  if (m.count < runs) s += " (" + std::to_string(m.count) + "/" + std::to_string(runs) + ")";
  return s;
}

std::string csvNumber(const MeanOf& m, int digits) { return m.count ? fixed(m.mean, digits) : ""; }

// ",lo,hi" of a mean's interval for table.csv (empty fields: no value).
std::string csvInterval(const MeanOf& m, int digits) {
  if (m.count == 0) return ",,";
  const stats::Estimate e = estimateOf(m);
  std::string s = ",";  // appended, not "," + ...: GCC 12 warns falsely (-Wrestrict) on that form
  s += fixed(e.ci.lo, digits);
  s += ",";
  s += fixed(e.ci.hi, digits);
  return s;
}

// "k/n [lo, hi]" of a row's collisions, and the paper's k of n with Fisher's exact p where known.
std::string collisionCell(const ReportRow& r) {
  const stats::Interval ci = collisionRate(r);
  std::string s = std::to_string(r.crashes) + "/" + std::to_string(r.complete) + " [" + fixed(ci.lo, 2) + ", " +
                  fixed(ci.hi, 2) + "]";
  return s;
}

std::string paperCollisionCell(const ReportRow& r) {
  if (r.paper_collisions < 0 || r.paper_runs <= 0) return "—";
  return std::to_string(r.paper_collisions) + "/" + std::to_string(r.paper_runs) +
         " (p = " + fixed(stats::fisherExact(r.crashes, r.complete, r.paper_collisions, r.paper_runs), 2) + ")";
}

}  // namespace

std::string reportMethodName(const nlohmann::json& m) {
  std::string name = m.value("method", std::string("?"));
  if (m.contains("switches") && m["switches"].is_object())
    for (const auto& [k, v] : m["switches"].items())
      if (v.is_boolean() && !v.get<bool>()) name += " -" + k;
  // The published code's defects that are on: "+published" when all are, else each by name.
  if (m.contains("reference_code") && m["reference_code"].is_object()) {
    std::string on;
    bool all = true;
    for (const auto& [k, v] : m["reference_code"].items()) {
      const bool set = v.is_boolean() && v.get<bool>();
      all = all && set;
      if (set) on += " +" + k;
    }
    name += all && !on.empty() ? " +published" : on;
  }
  return name;
}

const PaperRow* paperRow(const std::string& world, const std::string& method, const nlohmann::json& switches) {
  // The rows come from the method's registration: a run answers to the row of its world and of the one
  // switch it turns off (none: the full method).
  std::vector<std::string> off;
  if (switches.is_object())
    for (const auto& [k, v] : switches.items())
      if (v.is_boolean() && !v.get<bool>()) off.push_back(k);
  const MethodRegistration* entry = findRegistration(method);
  if (!entry || off.size() > 1) return nullptr;
  const std::string switched_off = off.empty() ? "" : off[0];
  for (const PaperRow& row : entry->info.paper_rows)
    if (world == row.world && switched_off == row.switched_off) return &row;
  return nullptr;
}

const PaperRow* paperRowNamed(const std::string& world, const std::string& report_method) {
  // "monospheres -ovde -dbof": the type, then the switches that are off.
  std::istringstream words(report_method);
  std::string type, word;
  words >> type;
  nlohmann::json switches = nlohmann::json::object();
  while (words >> word)
    if (word.size() > 1 && word[0] == '-') switches[word.substr(1)] = false;
  return paperRow(world, type, switches);
}

// The Table I world a run answers to: its world's paper_world (the authors' worlds), else its world.
std::string paperWorldOf(const nlohmann::json& m) {
  if (m.contains("paper_world") && m["paper_world"].is_string()) return m["paper_world"].get<std::string>();
  return m.value("world", std::string("?"));
}

bool isTableOneSweep(const SweepResults& results) {
  bool any = false;
  for (const ReportRun& run : results.runs) {
    if (!run.record) continue;
    const nlohmann::json& m = run.metrics;
    if (number(m, "duration_s", -1.0) != kPaperDurationS) return false;
    if (!paperRow(paperWorldOf(m), m.value("method", std::string()), m.value("switches", nlohmann::json())))
      return false;
    any = true;
  }
  return any;
}

std::string rowName(const ReportRow& row) {
  std::string name;
  for (const std::string& l : row.labels)
    if (l != row.world && !l.empty()) name += (name.empty() ? "" : " ") + l;
  return name.empty() ? row.method : name;
}

// Flags of the verified section: verified / claimed below this, falsely free volume above that.
constexpr double kFlagVerifiedShare = 0.75;
constexpr double kFlagFalselyFree = 0.3;

bool isSaturated(const ReportRow& row) { return row.complete > 0 && 2 * row.saturated > row.complete; }

stats::Estimate estimateOf(const MeanOf& m) { return stats::bootstrapMean(m.values); }

void addFrontEndProfile(ReportRow& row, const nlohmann::json& m) {
  if (!m.contains("frontend_profile") || !m["frontend_profile"].is_object()) return;
  const nlohmann::json& f = m["frontend_profile"];
  if (!f.contains("depth_bands") || !f["depth_bands"].is_array()) return;
  double wrong = 0.0, points = 0.0;
  for (size_t b = 0; b < f["depth_bands"].size(); ++b) {
    const nlohmann::json& band = f["depth_bands"][b];
    const double n = number(band, "points");
    if (b < 3 && n > 0) add(row.fe_median_m[b], number(band, "median_error_m"));
    wrong += n * number(band, "share_over_2_m"), points += n;
  }
  if (points > 0) add(row.fe_wrong_share, wrong / points);
  if (number(f, "tracks") > 0) add(row.fe_moved_share, number(f, "moved_over_0_3_m_share"));
}

stats::Interval collisionRate(const ReportRow& row) { return stats::wilson(row.crashes, row.complete); }

SweepResults loadSweepResults(const fs::path& dir) {
  const fs::path index = dir / "sweep.json";
  if (!fs::exists(index)) throw std::runtime_error(index.string() + ": not found (not a sweep directory?)");
  const auto j = readJsonFile(index);
  if (!j.is_object() || !j.contains("runs") || !j["runs"].is_array())
    throw std::runtime_error(index.string() + ": not a sweep index (no runs)");
  SweepResults r;
  r.dir = dir;
  // Strictly: every key the report reads, with its type; a bad one names the file and the key.
  auto bad = [&](const std::string& key, const std::string& why) {
    return std::runtime_error(index.string() + ": key '" + key + "': " + why);
  };
  if (j.contains("axes")) {
    if (!j["axes"].is_array()) throw bad("axes", "expected a list of names");
    for (size_t k = 0; k < j["axes"].size(); ++k) {
      if (!j["axes"][k].is_string()) throw bad("axes[" + std::to_string(k) + "]", "expected a name");
      r.axes.push_back(j["axes"][k].get<std::string>());
    }
  }
  for (size_t k = 0; k < j["runs"].size(); ++k) {
    const SweepRunRecord rec = readSweepRun(j["runs"][k], "runs[" + std::to_string(k) + "]", bad);
    ReportRun run;
    run.id = rec.id;
    run.seed = rec.seed;
    run.status = sweepRunStatusName(rec.status);
    run.labels = rec.labels;
    run.failure = rec.failure;
    const fs::path rd = dir / "runs" / run.id;
    if (run.status == "complete") {
      // A complete run whose directory is not the sweep's own, or whose metrics.json is missing,
      // truncated or incomplete, is a failed run.
      const std::string foreign = foreignRunDir(dir, run.id);
      MissionRecordRead read = foreign.empty() ? readMissionRecord(rd / "metrics.json") : MissionRecordRead{};
      if (!foreign.empty()) read.problem = foreign;
      if (read.record) {
        try {
          run.coverage = readCoverageCsv(rd / "coverage.csv");
        } catch (const InputFileError& e) {
          read.record.reset(), read.problem = e.what();
        }
      }
      if (read.record) {
        run.metrics = read.record->metrics;
        run.record = std::move(read.record);
      } else {
        run.status = "failed";
        run.failure.emplace();
        run.failure->problem = read.problem;
        std::fprintf(stderr, "report: run %s counts as failed: %s\n", terminalText(run.id).c_str(),
                     terminalText(read.problem).c_str());
      }
    }
    r.runs.push_back(std::move(run));
  }
  return r;
}

std::optional<double> timeToBoxShare(const std::vector<CoverageSample>& coverage, double share) {
  for (const CoverageSample& c : coverage)
    if (c.box_share >= share) return c.t_s;
  return std::nullopt;
}

// Verified coverage and map accuracy of a run (metrics.json; older records have neither).
void addVerified(ReportRow& row, const nlohmann::json& m, const MissionRecord& record) {
  const double area = record.area_m2;
  const nlohmann::json& cov = m["coverage"];
  if (cov.contains("verified_area_m2") && cov["verified_area_m2"].is_number()) {
    add(row.verified_area_m2, number(cov, "verified_area_m2"));
    if (area > 0) add(row.verified_share, number(cov, "verified_area_m2") / area);
  }
  if (record.earned_m3) add(row.earned_m3, *record.earned_m3);
  if (!m.contains("map_accuracy") || !m["map_accuracy"].is_object()) return;
  const nlohmann::json& a = m["map_accuracy"];
  if (a.contains("falsely_free_volume_share") && a["falsely_free_volume_share"].is_number())
    add(row.falsely_free_volume, number(a, "falsely_free_volume_share"));
  if (a.contains("falsely_free_element_share") && a["falsely_free_element_share"].is_number())
    add(row.falsely_free_elements, number(a, "falsely_free_element_share"));
}

std::vector<ReportRow> reportRows(const SweepResults& results) {
  const bool table_one = isTableOneSweep(results);
  std::vector<ReportRow> rows;
  for (const ReportRun& run : results.runs) {
    std::vector<std::string> labels;
    for (const auto& a : results.axes) labels.push_back(run.labels.count(a) ? run.labels.at(a) : "");
    auto it = std::find_if(rows.begin(), rows.end(), [&](const ReportRow& r) { return r.labels == labels; });
    if (it == rows.end()) {
      rows.push_back(ReportRow{});
      it = rows.end() - 1;
      it->labels = labels;
    }
    ReportRow& row = *it;
    ++row.runs;
    if (run.status == "failed") {
      // A failed run counts in the means with nothing explored and nothing earned: abstaining on a
      // bad seed must not raise a row.
      ++row.failed;
      add(row.area_m2, 0.0);
      add(row.earned_m3, 0.0);
      row.area_seeds.push_back(run.seed);
    }
    if (!run.record) continue;
    const nlohmann::json& m = run.metrics;
    ++row.complete;
    if (row.world.empty()) {
      row.world = paperWorldOf(m);
      row.method = reportMethodName(m);
      if (const PaperRow* p =
              table_one ? paperRow(row.world, m.value("method", std::string()), m.value("switches", nlohmann::json()))
                        : nullptr) {
        row.paper_mean_m2 = p->mean_area_m2, row.paper_max_m2 = p->max_area_m2;
        row.paper_runs = p->runs, row.paper_collisions = p->collisions;
      }
    }
    const nlohmann::json& cov = m["coverage"];
    const double a = run.record->area_m2;
    add(row.area_m2, a);
    row.area_seeds.push_back(run.seed);
    row.max_area_m2 = std::max(row.max_area_m2, a);
    if (const auto share = run.record->box_share) {
      add(row.box_share, *share);
      row.saturated += *share >= kSaturatedBoxShare;
    }
    row.vio_lost += run.record->status == RunStatus::kVioLost;
    addFrontEndProfile(row, m);
    addVerified(row, m, *run.record);
    if (const auto t = timeToBoxShare(run.coverage, 0.5)) add(row.t50_s, *t);
    if (const auto t = timeToBoxShare(run.coverage, 0.9)) add(row.t90_s, *t);
    const double flown = number(m, "distance_flown_m");
    if (flown > 0) add(row.area_per_100m, 100.0 * a / flown);
    if (cov.contains("longest_no_gain_s")) add(row.longest_no_gain_s, number(cov, "longest_no_gain_s"));
    add(row.rtf, number(m, "real_time_factor"));
    if (run.record->status == RunStatus::kCollided) {
      ++row.crashes;
      const nlohmann::json& c = m["collision"];
      const std::string kind = c.is_object() && c.contains("kind") && c["kind"].is_string()
                                   ? c["kind"].get<std::string>()
                                   : std::string("unknown");
      ++row.collisions_by_kind[kind];
    }
  }
  // Records from before the earned score carry none: a row's failed zeros alone are no score.
  for (ReportRow& row : rows)
    if (row.earned_m3.count == row.failed) row.earned_m3 = MeanOf{};
  return rows;
}

namespace {

// The row's axis labels as the first cells of a Markdown table line.
std::string labelCells(const ReportRow& r) {
  std::string s = "|";
  for (const auto& l : r.labels) s.append(" ").append(mdText(l)).append(" |");  // appends: GCC 12 -Wrestrict
  return s;
}

// A Markdown table head: the axes, then `columns`.
std::string tableHead(const SweepResults& results, const std::vector<std::string>& columns) {
  std::string head = "|", rule = "|";
  for (const auto& a : results.axes) head.append(" ").append(mdText(a)).append(" |"), rule += " --- |";
  for (const auto& c : columns) head += " " + c + " |", rule += " --- |";
  return head + "\n" + rule + "\n";
}

// A sweep that is not Table I: rows ranked by the earned score (docs/metrics.md), then by verified
// A, the claim beside them. Rows without the figures (records from before them) come last.
std::vector<ReportRow> rankedRows(std::vector<ReportRow> rows) {
  std::stable_sort(rows.begin(), rows.end(), [](const ReportRow& a, const ReportRow& b) {
    const auto key = [](const ReportRow& r) {
      return std::make_tuple(r.earned_m3.count > 0, r.earned_m3.count ? r.earned_m3.mean : 0.0,
                             r.verified_area_m2.count ? r.verified_area_m2.mean : -1.0);
    };
    return key(a) > key(b);
  });
  return rows;
}

// A run's earned score and verified A, as the Runs table of a ranked report shows them.
std::string earnedCells(const ReportRun& r) {
  const nlohmann::json& cov = r.metrics["coverage"];
  const bool verified = cov.is_object() && cov.contains("verified_area_m2") && cov["verified_area_m2"].is_number();
  return (r.record && r.record->earned_m3 ? fixed(*r.record->earned_m3, 0) : std::string("—")) + " | " +
         (verified ? fixed(cov["verified_area_m2"].get<double>(), 0) : std::string("—")) + " | ";
}

std::string rankedResultsSection(const SweepResults& results, const std::vector<ReportRow>& rows) {
  std::ostringstream o;
  o << "## Results\n\nRanked by the earned score: the truly free volume of the box a method declared where its "
       "camera, inside the box, came within 10 m, less what it declared inside obstacles or where its camera "
       "never looked; a run that ends in a collision earns 0 (docs/metrics.md, \"The earned score\"). Then "
       "verified A: the columns its free space earned (truly free and seen by the camera; \"Verified "
       "coverage\"), not the columns it claims. Means with their 95 % bootstrap interval over the row's seeds "
       "(percentile, "
    << stats::kDraws
    << " resamples, fixed seed); with fewer than 3 runs, {min, max}: a range, not an interval. ⚠: verified / "
       "claimed below "
    << fixed(kFlagVerifiedShare, 2)
    << ". Crashes: runs ended by a collision, k/n with the Wilson 95 % interval of the rate. Not a Table I sweep "
       "(not every run is a Table I row flown for the paper's 1200 s): the paper's figures and findings are not "
       "shown.\n\n"
    << tableHead(results, {"method type", "runs", "earned (m³)", "verified A (m²)", "A, claimed (m²)",
                           "verified / claimed", "crashes [95 % CI]"});
  for (const ReportRow& r : rows) {
    const bool low = r.verified_share.count > 0 && r.verified_share.mean < kFlagVerifiedShare;
    o << labelCells(r) << " " << (r.method.empty() ? "—" : mdText(r.method)) << " | " << r.complete;
    if (r.complete < r.runs) o << " of " << r.runs;
    o << " | " << intervalCell(r.earned_m3, r.complete, 0) << " | " << intervalCell(r.verified_area_m2, r.complete, 0)
      << " | " << intervalCell(r.area_m2, r.complete, 0) << " | " << intervalCell(r.verified_share, r.complete, 2)
      << (low ? " ⚠" : "") << " | " << (r.complete ? collisionCell(r) : "—") << " |\n";
  }
  return o.str();
}

// The paper's Table I layout (a Table I sweep), each mean with its interval; any other sweep's
// rows ranked by verified A.
std::string tableOneSection(const SweepResults& results, const std::vector<ReportRow>& rows) {
  if (!isTableOneSweep(results)) return rankedResultsSection(results, rows);
  std::ostringstream o;
  o << "## Table I layout\n\n"
    << "Mean A with its 95 % bootstrap interval over the row's seeds (percentile, " << stats::kDraws
    << " resamples, fixed seed; docs/sweeps.md, \"Intervals and verdicts\"). Crashes: runs ended by "
       "a collision, k/n with the Wilson 95 % interval of the rate"
    << "; the paper's count where §V-C gives it, with Fisher's exact p of the two counts.\n\n";
  // The earned score beside A when the runs recorded it (runs before it existed: no column).
  const bool earned = std::any_of(rows.begin(), rows.end(), [](const ReportRow& r) { return r.earned_m3.count > 0; });
  std::vector<std::string> head = {"method type", "runs",         "mean A (m²) [95 % CI]",
                                   "max A (m²)",  "paper mean A", "paper max A"};
  if (earned) head.push_back("earned (m³)");
  head.insert(head.end(), {"crashes [95 % CI]", "paper crashes (p)"});
  o << tableHead(results, head);
  for (const ReportRow& r : rows) {
    o << labelCells(r) << " " << (r.method.empty() ? "—" : mdText(r.method)) << " | " << r.complete;
    if (r.complete < r.runs) o << " of " << r.runs;
    o << " | " << intervalCell(r.area_m2, r.complete, 0) << " | " << (r.complete ? fixed(r.max_area_m2, 0) : "—")
      << " | " << (r.paper_mean_m2 ? fixed(*r.paper_mean_m2, 0) : "—") << " | "
      << (r.paper_max_m2 ? fixed(*r.paper_max_m2, 0) : "—") << " | "
      << (earned ? intervalCell(r.earned_m3, r.complete, 0) + " | " : "") << (r.complete ? collisionCell(r) : "—")
      << " | " << paperCollisionCell(r) << " |\n";
  }
  return o.str();
}

// Verified coverage and map accuracy per row (runs that recorded them).
std::string verifiedSection(const SweepResults& results, const std::vector<ReportRow>& rows) {
  std::ostringstream body;
  bool flagged = false;
  for (const ReportRow& r : rows) {
    if (r.verified_area_m2.count == 0 && r.falsely_free_volume.count == 0) continue;
    // A row that earns much less than it claims, or declares much of its free space inside
    // obstacles, is flagged where its figure stands.
    const bool low = r.verified_share.count > 0 && r.verified_share.mean < kFlagVerifiedShare;
    const bool false_free = r.falsely_free_volume.count > 0 && r.falsely_free_volume.mean > kFlagFalselyFree;
    flagged = flagged || low || false_free;
    body << labelCells(r) << " " << intervalCell(r.area_m2, r.complete, 0) << " | "
         << intervalCell(r.verified_area_m2, r.complete, 0) << " | " << intervalCell(r.verified_share, r.complete, 2)
         << (low ? " ⚠" : "") << " | " << intervalCell(r.falsely_free_volume, r.complete, 3) << (false_free ? " ⚠" : "")
         << " | " << intervalCell(r.falsely_free_elements, r.complete, 3) << " |\n";
  }
  if (body.str().empty()) return "";
  if (flagged)
    body << "\n⚠: verified / claimed below " << fixed(kFlagVerifiedShare, 2)
         << " (the row claims columns it did not earn: not seen, or not truly free), or a falsely free volume "
            "above "
         << fixed(kFlagFalselyFree, 2)
         << " (much of its declared free space lies inside obstacles). Rank such rows by verified A, not A.\n";
  return "\n## Verified coverage and map accuracy\n\nA is the method's own claim (the paper's metric: a column "
         "counts when a free-space element covers its node). Verified A counts a column only when the element, "
         "placed in the true frame, is truly free in that column and the camera saw the column (docs/metrics.md, "
         "\"Verified coverage\"); rankings of arbitrary methods use it. Falsely free: the share of the final map's "
         "declared free volume, and of its free elements, lying more than 0.5 m inside obstacles. Means over the "
         "row's runs with 95 % intervals.\n\n" +
         tableHead(results, {"A, claimed (m²)", "verified A (m²)", "verified / claimed", "falsely free volume",
                             "falsely free elements"}) +
         body.str();
}

// What the paper does not report, with intervals.
std::string beyondPaperSection(const SweepResults& results, const std::vector<ReportRow>& rows) {
  std::ostringstream o;
  o << "\n## Beyond the paper\n\n"
       "Box share: explored explorable columns of the exploration box / explorable columns. "
       "t50 / t90: simulated time to 50 % / 90 % of the box (over the runs that got there: k/n). "
       "A per 100 m: A / distance flown. Each with its 95 % bootstrap interval. No gain: longest stretch "
       "without coverage gain (mean). Collisions by the kind of object hit; VIO lost: runs ended by lost "
       "tracking.\n\n"
    << tableHead(results, {"box share", "t50 (s)", "t90 (s)", "A per 100 m", "no gain (s)", "textureless", "thin",
                           "textured", "other", "VIO lost", "RTF"});
  for (const ReportRow& r : rows) {
    auto kind = [&](const std::string& k) { return r.collisions_by_kind.count(k) ? r.collisions_by_kind.at(k) : 0; };
    const int other = r.crashes - kind("textureless") - kind("thin") - kind("textured");
    o << labelCells(r) << " " << intervalCell(r.box_share, r.complete, 2) << " | "
      << intervalCell(r.t50_s, r.complete, 0) << " | " << intervalCell(r.t90_s, r.complete, 0) << " | "
      << intervalCell(r.area_per_100m, r.complete, 0) << " | " << meanCell(r.longest_no_gain_s, r.complete, 0) << " | "
      << kind("textureless") << " | " << kind("thin") << " | " << kind("textured") << " | " << other << " | "
      << r.vio_lost << " | " << meanCell(r.rtf, r.complete, 2) << " |\n";
  }
  return o.str();
}

// The front-end error profile per row (runs with ground truth that recorded it).
std::string frontEndSection(const SweepResults& results, const std::vector<ReportRow>& rows) {
  std::ostringstream body;
  for (const ReportRow& r : rows) {
    if (r.fe_wrong_share.count == 0) continue;
    body << labelCells(r) << " " << intervalCell(r.fe_median_m[0], r.complete, 2) << " | "
         << intervalCell(r.fe_median_m[1], r.complete, 2) << " | " << intervalCell(r.fe_median_m[2], r.complete, 2)
         << " | " << intervalCell(r.fe_wrong_share, r.complete, 3) << " | "
         << intervalCell(r.fe_moved_share, r.complete, 2) << " |\n";
  }
  if (body.str().empty()) return "";
  return "\n## Front-end error profile\n\nThe SLAM points the method received, against the ground truth (never shown "
         "to "
         "the method; docs/perception.md): median distance to the nearest true surface by depth, the share of points "
         "more than 2 m off any surface (wrong points), the share of tracks whose published estimate moved more than "
         "0.3 m over its life; means over the row's runs with 95 % intervals.\n\n" +
         tableHead(results,
                   {"median error 0-5 m", "5-10 m", "10-20 m", "wrong points (> 2 m)", "tracks moved > 0.3 m"}) +
         body.str();
}

// The worlds where a row fills the box: there the area cannot tell speeds apart; t50 / t90 can.
std::string saturationSection(const std::vector<ReportRow>& rows) {
  std::vector<std::string> worlds;
  for (const ReportRow& r : rows)
    if (isSaturated(r) && std::find(worlds.begin(), worlds.end(), r.world) == worlds.end()) worlds.push_back(r.world);
  if (worlds.empty()) return "";
  std::ostringstream o;
  o << "\n## Where the box saturates\n\nA row is saturated when most of its runs explored at least "
    << fixed(100 * kSaturatedBoxShare, 0)
    << " % of the box. Its area then measures the box, not the method: a method twice as fast ends with the same A, "
       "and the paper's mean / max A cannot be compared with it. Compare such rows by the time to 50 % and 90 % of "
       "the box (95 % intervals over the runs that got there, k/n).\n\n"
       "| world | method | saturated runs | t50 (s) | t90 (s) |\n| --- | --- | --- | --- | --- |\n";
  // Rows of one world that share a method name (variants of one method, e.g. a Python method's
  // parameters) are told apart by their variant labels.
  const auto name = [&](const ReportRow& r) {
    const auto same = std::count_if(rows.begin(), rows.end(),
                                    [&](const ReportRow& q) { return q.world == r.world && q.method == r.method; });
    return same > 1 ? mdText(r.method) + " [" + mdText(rowName(r)) + "]" : mdText(r.method);
  };
  for (const std::string& w : worlds)
    for (const ReportRow& r : rows)
      if (r.world == w)
        o << "| " << mdText(w) << " | " << name(r) << (isSaturated(r) ? " (saturated)" : "") << " | " << r.saturated
          << "/" << r.complete << " | " << intervalCell(r.t50_s, r.complete, 0) << " | "
          << intervalCell(r.t90_s, r.complete, 0) << " |\n";
  return o.str();
}

// "ratio [lo, hi]".
std::string ratioText(const stats::Estimate& e) {
  return fixed(e.value, 2) + " [" + fixed(e.ci.lo, 2) + ", " + fixed(e.ci.hi, 2) + "]";
}

// The verified areas of a row with their seeds (every run of the row has one), or nullopt.
std::optional<ReportRow> verifiedAsArea(const ReportRow& r) {
  if (r.verified_area_m2.count != r.area_m2.count) return std::nullopt;
  ReportRow v = r;
  v.area_m2 = r.verified_area_m2;
  return v;
}

// Each row against its world's first row, independently and paired on common seeds; on verified A
// (`verified`: a sweep that is not Table I) or the paper's A.
std::string pairedSection(const std::vector<ReportRow>& all_rows, bool verified) {
  std::vector<ReportRow> rows;
  for (const ReportRow& r : all_rows) {
    if (!verified) {
      rows.push_back(r);
    } else if (auto v = verifiedAsArea(r)) {
      rows.push_back(*v);
    }
  }
  std::ostringstream body;
  for (const ReportRow& r : rows) {
    const ReportRow* ref = nullptr;
    for (const ReportRow& c : rows)
      if (c.world == r.world && c.area_m2.count > 0) {
        ref = &c;
        break;
      }
    if (!ref || ref == &r || r.area_m2.count == 0 || !(ref->area_m2.mean > 0)) continue;
    const PairedAreas p = pairedAreas(r, *ref);
    body << "| " << mdText(r.world) << " | " << mdText(rowName(r)) << " / " << mdText(rowName(*ref)) << " | "
         << ratioText(stats::bootstrapRatio(r.area_m2.values, ref->area_m2.values)) << " (" << r.area_m2.count << ", "
         << ref->area_m2.count << ") | ";
    if (p.a.size() >= 2 && stats::mean(p.b) > 0) {
      const auto rho = stats::correlation(p.a, p.b);
      body << ratioText(stats::bootstrapPairedRatio(p.a, p.b)) << " (" << p.a.size() << ") | "
           << (rho ? fixed(*rho, 2) : "—") << " |\n";
    } else {
      body << "— | — |\n";
    }
  }
  if (body.str().empty()) return "";
  return std::string("\n## Paired comparisons\n\nEach row's mean ") + (verified ? "verified A" : "A") +
         " over its world's first row's (in a ranked report, the leader's): independently (each row's "
         "seeds resampled on their own) and paired (runs with the same seed resampled together; r: the correlation "
         "of the pairs). Runs with the same seed share the world and every noise stream's seed; the pairing is "
         "tightest between a method and its own ablation, which fly the same until the switch first acts "
         "(docs/sweeps.md, \"Intervals and verdicts\").\n\n"
         "| world | rows | ratio, independent [95 % CI] (runs) | ratio, paired [95 % CI] (seeds) | r |\n"
         "| --- | --- | --- | --- | --- |\n" +
         body.str();
}

}  // namespace

PairedAreas pairedAreas(const ReportRow& a, const ReportRow& b) {
  PairedAreas p;
  for (size_t i = 0; i < a.area_seeds.size(); ++i)
    for (size_t j = 0; j < b.area_seeds.size(); ++j)
      if (a.area_seeds[i] == b.area_seeds[j]) {
        p.seeds.push_back(a.area_seeds[i]);
        p.a.push_back(a.area_m2.values[i]);
        p.b.push_back(b.area_m2.values[j]);
        break;
      }
  return p;
}

std::string reportMarkdown(const SweepResults& results, const std::vector<ReportRow>& rows) {
  std::ostringstream o;
  o << "# Sweep report: " << mdText(results.dir.string()) << "\n\n";
  int complete = 0, failed = 0, pending = 0, off_suite = 0, unranked = 0;
  for (const auto& r : results.runs)
    (r.status == "complete"    ? complete
     : r.status == "failed"    ? failed
     : r.status == "off-suite" ? off_suite
     : r.status == "unranked"  ? unranked
                               : pending)++;
  o << results.runs.size() << " runs: " << complete << " complete, " << failed << " failed, " << pending << " not run"
    << (results.suite.empty() ? "" : ", " + std::to_string(off_suite) + " off the suite " + mdText(results.suite))
    << (unranked ? ", " + std::to_string(unranked) + " not ranked" : "")
    << ". A = explored 2.5 m columns (m², unbounded, VIO frame, as the paper's Table I).\n\n";
  // Whose seals were checked: the evaluator's key, or none (a researcher's own report).
  o << (results.sealed_under.empty()
            ? std::string("Seals: not verified under an evaluator key (`msbench report --key FILE` ranks only "
                          "records sealed under it; docs/integrity.md).\n\n")
            : "Seals: verified under evaluator key " + results.sealed_under +
                  "; only records sealed under it and unchanged are ranked (docs/integrity.md).\n\n");
  // Runs not ranked (unsealed, unconfined): set aside, said first.
  if (unranked > 0) {
    o << "## Not ranked\n\nThese runs completed, but only sealed records of methods that ran confined or "
         "compiled into msbench are ranked (docs/metrics.md, \"What is ranked\"); they are in no row, ranking, "
         "ratio or finding below.\n\n| run | why |\n| --- | --- |\n";
    for (const ReportRun& r : results.runs)
      if (r.status == "unranked") o << "| " << mdText(r.id) << " | " << mdText(r.unranked) << " |\n";
    o << "\n";
  }
  // Runs whose settings are not the suite's: set aside, said first.
  if (off_suite > 0) {
    o << "## Off the suite\n\nThese runs flew with settings the suite (" << mdText(results.suite)
      << ") does not fix; they are in no row, ranking or finding below (docs/sweeps.md, \"Suites\").\n\n"
         "| run | why |\n| --- | --- |\n";
    for (const ReportRun& r : results.runs)
      if (r.status == "off-suite") o << "| " << mdText(r.id) << " | " << mdText(r.off_suite) << " |\n";
    o << "\n";
  }
  // Failed runs first: a table with a hole in it must say so before anything else.
  if (failed > 0) {
    o << "## Failed runs\n\nThese runs have no result; each counts in its row with A = 0 and score 0 (a method "
         "that fails is never better off than one that flies; docs/metrics.md). Re-running the same "
         "`msbench sweep` command redoes them.\n\n| run | ended by | last progress | fatal signal report | log |\n"
         "| --- | --- | --- | --- | --- |\n";
    for (const ReportRun& r : results.runs) {
      if (r.status != "failed") continue;
      const SweepRunFailure f = r.failure.value_or(SweepRunFailure{});
      auto text = [](const std::string& v) { return v.empty() ? std::string("—") : mdText(v); };
      const std::string ended =
          f.signal ? "signal " + std::to_string(f.signal) + (f.signal_name.empty() ? "" : " (" + f.signal_name + ")")
                   : "exit code " + std::to_string(f.exit_code);
      const std::string why = !f.problem.empty() ? mdText(f.problem)
                              : !f.limit.empty() ? mdText(f.limit)
                                                 : text(f.fatal);
      o << "| " << mdText(r.id) << " | " << (!f.problem.empty() ? std::string("unreadable results") : mdText(ended))
        << " | " << text(f.last_progress) << " | " << why << " | logs/" << mdText(r.id) << ".log |\n";
    }
    o << "\n";
  }
  // Every table in one order: Table I's, or (any other sweep) the ranking of the Results.
  const bool table_one = isTableOneSweep(results);
  const std::vector<ReportRow> ordered = table_one ? rows : rankedRows(rows);
  o << tableOneSection(results, ordered) << verifiedSection(results, ordered) << beyondPaperSection(results, ordered)
    << frontEndSection(results, ordered) << saturationSection(ordered) << pairedSection(ordered, !table_one);
  // Every run, with its collision (and what it earned, in a ranked report).
  o << "\n## Runs\n\n| run | status | A (m²) | " << (table_one ? "" : "earned (m³) | verified A (m²) | ")
    << "box share | time (s) | tracked (mean) | drift (m) | collision |\n"
    << "| --- | --- | --- | " << (table_one ? "" : "--- | --- | ") << "--- | --- | --- | --- | --- |\n";
  // Runs not yet run: the first kListedPending by name, the rest counted (a sweep of 100 000
  // pending runs reports in seconds; report_runs.csv lists every run).
  constexpr int kListedPending = 20;
  int pending_shown = 0, pending_more = 0;
  for (const ReportRun& r : results.runs) {
    const nlohmann::json& m = r.metrics;
    if (!m.is_object()) {
      if (r.status == "pending" && pending_shown == kListedPending) {
        ++pending_more;
        continue;
      }
      pending_shown += r.status == "pending";
      o << "| " << mdText(r.id) << " | " << mdText(r.status) << " | — | — | — | — | — | — |"
        << (table_one ? "" : " — | — |") << "\n";
      continue;
    }
    std::string hit = "—";
    if (m.contains("collision") && m["collision"].is_object()) {
      const auto& c = m["collision"];
      hit = (c.contains("object") && c["object"].is_string() ? c["object"].get<std::string>()
                                                             : c.value("world_geom", "?")) +
            (c.contains("kind") && c["kind"].is_string() ? " (" + c["kind"].get<std::string>() + ")" : "");
      // The audit's cause and what the map knew (docs/planner.md, "Collision audit").
      if (c.contains("audit") && c["audit"].is_object()) {
        const auto& a = c["audit"];
        hit += ": " + a.value("cause", std::string("?")) + " — " + std::to_string(a.value("slam_points_on_part", 0)) +
               " SLAM points on the part, " + std::to_string(a.value("map_points_on_object", 0)) +
               " map points on the object, drift " + fixed(number(a, "vio_drift_m"), 1) + " m" +
               (a.value("inside_free_space", false) ? ", inside free space" : "");
      }
    }
    const auto& cov = m["coverage"];
    o << "| " << mdText(r.id) << " | " << mdText(m.value("status", std::string("?"))) << " | "
      << fixed(number(cov, "area_m2"), 0) << " | ";
    if (!table_one) o << earnedCells(r);
    o << (cov.is_object() && cov.contains("box_share") && cov["box_share"].is_number()
              ? fixed(cov["box_share"].get<double>(), 2)
              : "—")
      << " | " << fixed(number(m, "sim_time_s"), 0) << " | "
      << (m.contains("perception") ? fixed(number(m["perception"], "tracked_mean"), 0) : "—") << " | "
      << fixed(number(m, "final_drift_m"), 2) << " | " << mdText(hit) << " |\n";
  }
  if (pending_more)
    o << "| … and " << pending_more << " more pending | pending | — | — | — | — | — | — |"
      << (table_one ? "" : " — | — |") << "\n";
  return o.str();
}

std::string reportTableCsv(const SweepResults& results, const std::vector<ReportRow>& rows) {
  std::ostringstream o;
  // The axes' columns first; a fixed column named like an axis is renamed (unique headers).
  const auto axis = [&](const char* n) {
    return std::find(results.axes.begin(), results.axes.end(), n) != results.axes.end();
  };
  for (const auto& a : results.axes) o << csvField(a) << ",";
  o << (axis("world") ? "world_name" : "world") << "," << (axis("method") ? "method_type" : "method")
    << ",runs,complete,failed,crashes,mean_area_m2,max_area_m2,paper_mean_area_m2,paper_max_area_m2,"
       "mean_box_share,t50_s,t50_runs,t90_s,t90_runs,area_per_100m,longest_no_gain_s,collisions_textureless,"
       "collisions_thin,collisions_textured,mean_rtf,area_ci_lo,area_ci_hi,box_share_ci_lo,box_share_ci_hi,"
       "t50_ci_lo,t50_ci_hi,t90_ci_lo,t90_ci_hi,area_per_100m_ci_lo,area_per_100m_ci_hi,collision_rate_ci_lo,"
       "collision_rate_ci_hi,paper_runs,paper_collisions,collisions_fisher_p,vio_lost,saturated_runs,saturated,"
       "mean_verified_area_m2,verified_area_ci_lo,verified_area_ci_hi,verified_share,falsely_free_volume_share,"
       "falsely_free_volume_ci_lo,falsely_free_volume_ci_hi,falsely_free_element_share\n";
  for (const ReportRow& r : rows) {
    for (const auto& l : r.labels) o << csvField(l) << ",";
    auto kind = [&](const std::string& k) { return r.collisions_by_kind.count(k) ? r.collisions_by_kind.at(k) : 0; };
    o << csvField(r.world) << "," << csvField(r.method) << "," << r.runs << "," << r.complete << "," << r.failed << ","
      << r.crashes << "," << csvNumber(r.area_m2, 1) << "," << (r.complete ? fixed(r.max_area_m2, 1) : "") << ","
      << (r.paper_mean_m2 ? fixed(*r.paper_mean_m2, 0) : "") << "," << (r.paper_max_m2 ? fixed(*r.paper_max_m2, 0) : "")
      << "," << csvNumber(r.box_share, 4) << "," << csvNumber(r.t50_s, 1) << "," << r.t50_s.count << ","
      << csvNumber(r.t90_s, 1) << "," << r.t90_s.count << "," << csvNumber(r.area_per_100m, 1) << ","
      << csvNumber(r.longest_no_gain_s, 1) << "," << kind("textureless") << "," << kind("thin") << ","
      << kind("textured") << "," << csvNumber(r.rtf, 3) << csvInterval(r.area_m2, 1) << csvInterval(r.box_share, 4)
      << csvInterval(r.t50_s, 1) << csvInterval(r.t90_s, 1) << csvInterval(r.area_per_100m, 1);
    const stats::Interval rate = collisionRate(r);
    o << "," << (r.complete ? fixed(rate.lo, 4) + "," + fixed(rate.hi, 4) : std::string(","));
    const bool paper_count = r.paper_collisions >= 0 && r.paper_runs > 0;
    o << "," << (r.paper_runs ? std::to_string(r.paper_runs) : "") << ","
      << (paper_count ? std::to_string(r.paper_collisions) : "") << ","
      << (paper_count ? fixed(stats::fisherExact(r.crashes, r.complete, r.paper_collisions, r.paper_runs), 4) : "")
      << "," << r.vio_lost << "," << r.saturated << "," << (isSaturated(r) ? "yes" : "no") << ","
      << csvNumber(r.verified_area_m2, 1) << csvInterval(r.verified_area_m2, 1) << "," << csvNumber(r.verified_share, 4)
      << "," << csvNumber(r.falsely_free_volume, 4) << csvInterval(r.falsely_free_volume, 4) << ","
      << csvNumber(r.falsely_free_elements, 4) << "\n";
  }
  return o.str();
}

std::string reportRunsCsv(const SweepResults& results) {
  std::ostringstream o;
  o << "id,world,series,status,run_status,dir,area_m2,verified_area_m2,score_earned_m3\n";
  for (const ReportRun& r : results.runs) {
    const std::string world = r.metrics.is_object() ? r.metrics.value("world", std::string("?")) : "";
    // The series: the run's labels except the one naming its world (one line per method/variant).
    std::string series;
    for (const auto& a : results.axes) {
      const std::string l = r.labels.count(a) ? r.labels.at(a) : "";
      if (l == world) continue;
      series += (series.empty() ? "" : "-") + l;
    }
    if (series.empty()) series = r.metrics.is_object() ? reportMethodName(r.metrics) : "run";
    // The claimed and verified areas of a complete run (its record, checked when loaded).
    std::string claimed, verified, earned;
    if (r.status == "complete" && r.metrics.is_object() && r.metrics.contains("coverage")) {
      const nlohmann::json& cov = r.metrics["coverage"];
      if (cov.contains("area_m2") && cov["area_m2"].is_number()) claimed = fixed(cov["area_m2"].get<double>(), 1);
      if (cov.contains("verified_area_m2") && cov["verified_area_m2"].is_number())
        verified = fixed(cov["verified_area_m2"].get<double>(), 1);
      const nlohmann::json* score = r.metrics.contains("score") ? &r.metrics["score"] : nullptr;
      if (score && score->is_object() && score->contains("earned") && (*score)["earned"].is_number())
        earned = fixed((*score)["earned"].get<double>(), 1);
    }
    o << csvField(r.id) << "," << csvField(world) << "," << csvField(series) << "," << r.status << ","
      << csvField(r.metrics.is_object() ? r.metrics.value("status", std::string()) : "") << ","
      << csvField((results.dir / "runs" / r.id).string()) << "," << claimed << "," << verified << "," << earned << "\n";
  }
  return o.str();
}

}  // namespace msb
