// The paper's findings as checks: for each kind of check, a hand-built sweep that passes and
// one that fails, and rows that are missing give "n/a".
#include "tools/sweep/findings.h"

#include <gtest/gtest.h>

namespace msb {
namespace {

// A complete run of `method` (with `off` switched off) in `world` covering `area` m².
ReportRun madeRun(const std::string& world, const std::string& type, const std::string& off, double area,
                  const std::string& hit_kind = "", double box_share = 0.5) {
  static int n = 0;
  ReportRun r;
  r.id = world + "-" + type + off + "-s" + std::to_string(++n);
  r.labels = {{"world", world}, {"method", type + off}};
  r.status = "complete";
  nlohmann::json switches = nlohmann::json::object();
  if (!off.empty()) switches[off] = false;
  r.metrics = {{"world", world},
               {"method", type},
               {"switches", switches},
               {"status", hit_kind.empty() ? "completed" : "collided"},
               {"coverage", {{"area_m2", area}, {"box_share", box_share}}}};
  if (!hit_kind.empty()) r.metrics["collision"] = {{"object", "x"}, {"kind", hit_kind}};
  return r;
}

FindingResult check(const std::string& id, const std::vector<ReportRun>& runs) {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  s.runs = runs;
  const auto rows = reportRows(s);
  for (const Finding& f : findingsTable())
    if (f.id == id) return evaluateFindings(s, rows, {f}).front();
  ADD_FAILURE() << "no finding " << id;
  return {};
}

TEST(Findings, RatioAtLeastPassesAtTwiceTheGridAndFailsBelow) {
  auto r = check("ms_vs_grid_cave", {madeRun("cave", "monospheres", "", 5000), madeRun("cave", "grid_random", "", 2000)});
  EXPECT_EQ(r.status, "pass");
  EXPECT_EQ(r.measured, "5000 / 2000 = 2.50 (1 and 1 run)");
  r = check("ms_vs_grid_cave", {madeRun("cave", "monospheres", "", 3000), madeRun("cave", "grid_random", "", 2000)});
  EXPECT_EQ(r.status, "fail");
  EXPECT_EQ(check("ms_vs_grid_cave", {madeRun("cave", "monospheres", "", 3000)}).status, "n/a");
}

TEST(Findings, RatioAtMostHoldsTheNoOvdeAblationBelowAThird) {
  EXPECT_EQ(check("no_ovde_urban", {madeRun("urban", "monospheres", "", 4000), madeRun("urban", "monospheres", "ovde", 800)}).status,
            "pass");
  EXPECT_EQ(check("no_ovde_urban", {madeRun("urban", "monospheres", "", 4000), madeRun("urban", "monospheres", "ovde", 3000)}).status,
            "fail");
}

TEST(Findings, TheAblationOrderNeedsEachStepAndTheNearTie) {
  auto order = [](double full, double vpb, double fff, double dbof, double ovde) {
    return check("ablation_order_urban",
                 {madeRun("urban", "monospheres", "", full), madeRun("urban", "monospheres", "vpb", vpb),
                  madeRun("urban", "monospheres", "fff", fff), madeRun("urban", "monospheres", "dbof", dbof),
                  madeRun("urban", "monospheres", "ovde", ovde)});
  };
  const auto ok = order(4900, 3700, 2500, 2300, 750);
  EXPECT_EQ(ok.status, "pass");
  EXPECT_EQ(ok.measured, "4900 > 3700 > 2500 ≈ 2300 > 750");
  EXPECT_EQ(order(4900, 5000, 2500, 2300, 750).status, "fail");  // no_vpb above the full method
  EXPECT_EQ(order(4900, 3700, 3600, 1500, 750).status, "fail");  // no_fff and no_dbof far apart
}

TEST(Findings, NoCollisionInTheCave) {
  EXPECT_EQ(check("cave_no_collision", {madeRun("cave", "monospheres", "", 5000), madeRun("cave", "grid_random", "", 2000)}).status,
            "pass");
  const auto r = check("cave_no_collision",
                       {madeRun("cave", "monospheres", "", 5000), madeRun("cave", "grid_random", "", 2000, "textured")});
  EXPECT_EQ(r.status, "fail");
  EXPECT_EQ(r.measured, "1 collision in 2 runs");
}

TEST(Findings, UrbanCollisionsOnlyOnTexturelessOrThinObjects) {
  EXPECT_EQ(check("urban_collision_kinds", {madeRun("urban", "monospheres", "", 4000, "textureless"),
                                            madeRun("urban", "grid_random", "", 2000, "thin")})
                .status,
            "pass");
  EXPECT_EQ(check("urban_collision_kinds", {madeRun("urban", "monospheres", "", 4000, "textureless"),
                                            madeRun("urban", "grid_random", "", 2000, "textured")})
                .status,
            "fail");
}

TEST(Findings, MonoSpheresUrbanCollisionsAfterTheMajorityOfTheBox) {
  EXPECT_EQ(check("urban_collisions_late", {madeRun("urban", "monospheres", "", 4000, "textureless", 0.7),
                                            madeRun("urban", "monospheres", "", 4000)})
                .status,
            "pass");
  const auto r = check("urban_collisions_late", {madeRun("urban", "monospheres", "", 4000, "textureless", 0.7),
                                                 madeRun("urban", "monospheres", "", 2000, "textureless", 0.3)});
  EXPECT_EQ(r.status, "fail");
  EXPECT_EQ(r.measured, "2 collisions in 2 runs, box share at contact 0.70, 0.30");
}

TEST(Findings, TheMarkdownAndCsvCarryEveryFinding) {
  SweepResults s;
  s.axes = {"world", "method"};
  s.runs = {madeRun("cave", "monospheres", "", 5000), madeRun("cave", "grid_random", "", 2000)};
  const auto findings = evaluateFindings(s, reportRows(s));
  ASSERT_EQ(findings.size(), findingsTable().size());
  const std::string md = findingsMarkdown(findings), csv = findingsCsv(findings);
  EXPECT_NE(md.find("| ✓ | MonoSpheres covers at least twice the grid baseline's mean A in the cave | 5000 / 2000 = 2.50"),
            std::string::npos)
      << md;
  EXPECT_NE(csv.find("ms_vs_grid_cave,\"MonoSpheres covers at least twice the grid baseline's mean A in the cave\",pass,"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("ms_vs_grid_urban,"), std::string::npos);
  EXPECT_NE(csv.find(",n/a,"), std::string::npos);
}

}  // namespace
}  // namespace msb
