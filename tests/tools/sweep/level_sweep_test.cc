// Ablations across levels: the ratio of each method to the full method per level, paired on
// seeds, and the lowest level at which it costs area, on hand-built results with known answers.
#include "tools/sweep/level_sweep.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

// A complete urban run with the fields the report reads.
ReportRun levelRun(const std::string& level, const std::string& method, uint64_t seed, double area) {
  ReportRun r;
  r.id = level + "-" + method + "-s" + std::to_string(seed);
  r.labels = {{"frontend", level}, {"method", method}};
  r.seed = seed;
  r.status = "complete";
  r.metrics = {{"world", "urban"},
               {"method", "monospheres"},
               {"switches", {{"dbof", method != "no_dbof"}, {"fff", method != "no_fff"}}},
               {"status", "completed"},
               {"distance_flown_m", 200.0},
               {"real_time_factor", 2.0},
               {"sim_time_s", 100.0},
               {"determinism_hash", "0123456789abcdef"},
               {"coverage", {{"area_m2", area}, {"box_share", nullptr}, {"longest_no_gain_s", 30.0}}}};
  r.record = missionRecordOf(r.metrics, r.id + "/metrics.json").record;
  return r;
}

// no_dbof matches the full method when clean and loses half its area when severe; no_fff never
// differs (up to seed-to-seed noise that the pairing removes).
SweepResults levelResults() {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"frontend", "method"};
  const double full[] = {1000, 1400, 800, 1200};
  for (const std::string level : {"clean", "severe"})
    for (const std::string method : {"monospheres", "no_dbof", "no_fff"})
      for (uint64_t seed = 1; seed <= 4; ++seed) {
        const double f = full[seed - 1] * (level == "severe" ? 0.8 : 1.0);
        const double a = method == "no_dbof" && level == "severe" ? 0.5 * f
                         : method == "monospheres"                ? f
                                                                  : f * (1.0 + 0.01 * double(seed % 2));
        s.runs.push_back(levelRun(level, method, seed, a));
      }
  return s;
}

TEST(LevelSweep, RatiosPerLevelArePairedAndTheLowestCostlyLevelIsNamed) {
  const SweepResults s = levelResults();
  const auto ls = levelSweep(s, reportRows(s));
  ASSERT_TRUE(ls.has_value());
  EXPECT_EQ(ls->axis, "frontend");
  EXPECT_EQ(ls->levels, (std::vector<std::string>{"clean", "severe"}));
  EXPECT_EQ(ls->reference_method, "monospheres");
  ASSERT_EQ(ls->cells.size(), 4u);  // two ablations × two levels
  for (const LevelCell& c : ls->cells) {
    EXPECT_EQ(c.pairs, 4);
    EXPECT_EQ(c.world, "urban");
    if (c.method == "no_dbof" && c.level == "severe") {
      EXPECT_NEAR(c.ratio.value, 0.5, 1e-12);
      EXPECT_LT(c.ratio.ci.hi, 1.0);
    } else {
      EXPECT_NEAR(c.ratio.value, 1.0, 0.01);
      EXPECT_GE(c.ratio.ci.hi, 1.0);
    }
  }
  const std::string md = levelSweepMarkdown(*ls);
  EXPECT_NE(md.find("| no_dbof | 1.00 [1.00, 1.01] | 0.50 [0.50, 0.50] | `severe` |"), std::string::npos) << md;
  EXPECT_NE(md.find("| no_fff |"), std::string::npos);
  EXPECT_NE(md.find("none of these levels"), std::string::npos);
  const auto clean = rowsAtLevel(s, reportRows(s), *ls, 0);
  ASSERT_EQ(clean.size(), 3u);  // the paper's findings are checked on these
  for (const ReportRow& r : clean) EXPECT_EQ(r.labels[0], "clean");
  const std::string csv = levelSweepCsv(*ls);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "world,level_index,level,method,ratio,lo,hi,pairs");
  EXPECT_NE(csv.find("urban,1,severe,no_dbof,0.500000,0.500000,0.500000,4"), std::string::npos) << csv;
}

TEST(LevelSweep, OnlyASweepWithAMethodAxisAndOneLevelAxisIsALevelSweep) {
  SweepResults s = levelResults();
  s.axes = {"method"};  // no level axis
  for (auto& r : s.runs) r.labels.erase("frontend");
  EXPECT_FALSE(levelSweep(s, reportRows(s)).has_value());
  SweepResults two = levelResults();
  two.axes = {"frontend", "light", "method"};  // two level axes
  for (auto& r : two.runs) r.labels["light"] = "noon";
  EXPECT_FALSE(levelSweep(two, reportRows(two)).has_value());
  SweepResults no_method = levelResults();
  no_method.axes = {"frontend", "variant"};
  for (auto& r : no_method.runs) r.labels["variant"] = r.labels["method"], r.labels.erase("method");
  EXPECT_FALSE(levelSweep(no_method, reportRows(no_method)).has_value());
}

}  // namespace
}  // namespace msb
