// The paper's findings as checks: for each kind of check, hand-built sweeps whose verdict holds,
// fails or is undecided, and rows that are missing give "n/a".
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
               {"sim_time_s", 100.0},
               {"duration_s", 1200.0},
               {"determinism_hash", "0123456789abcdef"},
               {"coverage", {{"area_m2", area}, {"box_share", box_share}}}};
  if (!hit_kind.empty()) r.metrics["collision"] = {{"object", "x"}, {"kind", hit_kind}};
  r.record = missionRecordOf(r.metrics, r.id + "/metrics.json").record;
  return r;
}

FindingResult check(const std::string& id, const std::vector<ReportRun>& runs) {
  SweepResults s;
  s.dir = "/nowhere";
  s.axes = {"world", "method"};
  s.runs = runs;
  const auto rows = reportRows(s);
  for (const Finding& f : findingsTable())
    if (f.id == id) {
      FindingResult r = evaluateFindings(s, rows, {f}).front();
      r.finding = &f;  // the table's entry, not the evaluated copy's (gone after this call)
      return r;
    }
  ADD_FAILURE() << "no finding " << id;
  return {};
}

// Two runs of a row, at `area` and 2 % above it (a row needs two runs for an interval).
std::vector<ReportRun> twoRuns(const std::string& world, const std::string& type, const std::string& off, double area) {
  return {madeRun(world, type, off, area), madeRun(world, type, off, area * 1.02)};
}

std::vector<ReportRun> joined(std::initializer_list<std::vector<ReportRun>> parts) {
  std::vector<ReportRun> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

TEST(Findings, RatioAtLeastHoldsAtTwiceTheGridFailsBelowAndIsUndecidedAcross) {
  auto r = check("ms_vs_grid_cave",
                 joined({twoRuns("cave", "monospheres", "", 5000), twoRuns("cave", "grid_random", "", 2000)}));
  EXPECT_EQ(r.status, "holds");
  EXPECT_EQ(r.measured.rfind("5050 / 2020 = 2.50 [", 0), 0u) << r.measured;
  EXPECT_EQ(r.paper, "7627 / 3171 = 2.41 (3 and 3 runs)");  // from the method registry
  r = check("ms_vs_grid_cave",
            joined({twoRuns("cave", "monospheres", "", 3000), twoRuns("cave", "grid_random", "", 2000)}));
  EXPECT_EQ(r.status, "fails");
  // 3000 and 5000 against 2000 and 2100: 1.95 with an interval across 2.
  r = check("ms_vs_grid_cave", {madeRun("cave", "monospheres", "", 3000), madeRun("cave", "monospheres", "", 5000),
                                madeRun("cave", "grid_random", "", 2000), madeRun("cave", "grid_random", "", 2100)});
  EXPECT_EQ(r.status, "undecided");
  ASSERT_TRUE(r.seeds_to_decide.has_value());
  EXPECT_GT(*r.seeds_to_decide, 2);
  // One run a row: no interval, no verdict.
  r = check("ms_vs_grid_cave", {madeRun("cave", "monospheres", "", 5000), madeRun("cave", "grid_random", "", 2000)});
  EXPECT_EQ(r.status, "undecided");
  EXPECT_EQ(r.measured, "5000 / 2000 = 2.50 [2.50, 2.50] (1 and 1 run)");
  EXPECT_FALSE(r.seeds_to_decide.has_value());
  EXPECT_EQ(check("ms_vs_grid_cave", {madeRun("cave", "monospheres", "", 3000)}).status, "n/a");
}

TEST(Findings, ATableUnderThePublishedCodeAnswersTheSameFindings) {
  // Rows named "monospheres +published" (method.reference_code) are the paper's MonoSpheres rows.
  std::vector<ReportRun> runs =
      joined({twoRuns("cave", "monospheres", "", 5000), twoRuns("cave", "grid_random", "", 2000)});
  for (ReportRun& r : runs)
    if (r.metrics["method"] == "monospheres") {
      r.metrics["reference_code"] = {{"path_resend_8s", true}, {"safety_cost_inverted", true}};
      r.record = missionRecordOf(r.metrics, r.id + "/metrics.json").record;
    }
  const FindingResult r = check("ms_vs_grid_cave", runs);
  EXPECT_EQ(r.status, "holds");
  EXPECT_EQ(r.measured.rfind("5050 / 2020 = 2.50 [", 0), 0u) << r.measured;
}

// The area findings once more on verified A: a grid that claims free space it never verified
// fails the ratio on the paper's A and holds it on verified A; without verified A, nothing.
TEST(Findings, AreaFindingsAreRepeatedOnVerifiedArea) {
  auto verified = [](ReportRun r, double v) {
    r.metrics["coverage"]["verified_area_m2"] = v;
    r.record = missionRecordOf(r.metrics, r.id + "/metrics.json").record;
    return r;
  };
  const std::vector<ReportRun> runs = {verified(madeRun("cave", "monospheres", "", 3000), 3000),
                                       verified(madeRun("cave", "monospheres", "", 3060), 3060),
                                       verified(madeRun("cave", "grid_random", "", 2000), 1000),
                                       verified(madeRun("cave", "grid_random", "", 2040), 1020)};
  const FindingResult r = check("ms_vs_grid_cave", runs);
  EXPECT_EQ(r.status, "fails");
  EXPECT_EQ(r.verified_status, "holds");
  EXPECT_EQ(r.verified_measured.rfind("3030 / 1010 = 3.00 [", 0), 0u) << r.verified_measured;
  EXPECT_NE(findingsMarkdown({r}).find("on verified A"), std::string::npos);
  EXPECT_NE(findingsCsv({r}).find(",holds,\"3030 / 1010"), std::string::npos) << findingsCsv({r});
  // A collision finding is not about A; runs without verified A leave it out.
  EXPECT_EQ(check("cave_no_collision", runs).verified_status, "");
  const FindingResult plain = check(
      "ms_vs_grid_cave", joined({twoRuns("cave", "monospheres", "", 3000), twoRuns("cave", "grid_random", "", 2000)}));
  EXPECT_EQ(plain.verified_status, "");
  EXPECT_EQ(findingsMarkdown({plain}).find("on verified A"), std::string::npos);
}

TEST(Findings, RatioAtMostHoldsTheNoOvdeAblationBelowAThird) {
  EXPECT_EQ(check("no_ovde_urban",
                  joined({twoRuns("urban", "monospheres", "", 4000), twoRuns("urban", "monospheres", "ovde", 800)}))
                .status,
            "holds");
  EXPECT_EQ(check("no_ovde_urban",
                  joined({twoRuns("urban", "monospheres", "", 4000), twoRuns("urban", "monospheres", "ovde", 3000)}))
                .status,
            "fails");
}

TEST(Findings, TheAblationOrderNeedsEachStepAndTheNearTie) {
  auto order = [](double full, double vpb, double fff, double dbof, double ovde) {
    return check("ablation_order_urban",
                 joined({twoRuns("urban", "monospheres", "", full), twoRuns("urban", "monospheres", "vpb", vpb),
                         twoRuns("urban", "monospheres", "fff", fff), twoRuns("urban", "monospheres", "dbof", dbof),
                         twoRuns("urban", "monospheres", "ovde", ovde)}));
  };
  const auto ok = order(4900, 3700, 2500, 2300, 750);
  EXPECT_EQ(ok.status, "holds");
  EXPECT_EQ(ok.measured.rfind("4949 > 3737 > 2525 ≈ 2323 > 758 (neighbour ratios: 1.32 [", 0), 0u) << ok.measured;
  EXPECT_EQ(ok.paper, "4919 > 3697 > 2470 ≈ 2308 > 747");
  EXPECT_EQ(order(4900, 5000, 2500, 2300, 750).status, "fails");  // no_vpb above the full method
  EXPECT_EQ(order(4900, 3700, 3600, 1500, 750).status, "fails");  // no_fff and no_dbof far apart
}

TEST(Findings, NoCollisionInTheCave) {
  EXPECT_EQ(
      check("cave_no_collision", {madeRun("cave", "monospheres", "", 5000), madeRun("cave", "grid_random", "", 2000)})
          .status,
      "holds");
  // One collision in two runs cannot be told from the paper's 0 of 6 (Fisher's p = 0.25).
  const auto r = check("cave_no_collision", {madeRun("cave", "monospheres", "", 5000),
                                             madeRun("cave", "grid_random", "", 2000, "textured")});
  EXPECT_EQ(r.status, "undecided");
  EXPECT_EQ(r.measured, "1 collision in 2 runs (rate 0.50 [0.09, 0.91]), exact test against the paper's p = 0.250");
  EXPECT_EQ(r.paper, "0 collisions in 6 runs");
  // Six of six can (p = 2 / 924).
  std::vector<ReportRun> all;
  for (int k = 0; k < 3; ++k)
    all.push_back(madeRun("cave", "monospheres", "", 5000, "textured")),
        all.push_back(madeRun("cave", "grid_random", "", 2000, "textured"));
  const auto six = check("cave_no_collision", all);
  EXPECT_EQ(six.status, "fails");
  EXPECT_NEAR(*six.p_value, 2.0 / 924, 1e-9);
}

TEST(Findings, UrbanCollisionsOnlyOnTexturelessOrThinObjects) {
  EXPECT_EQ(check("urban_collision_kinds", {madeRun("urban", "monospheres", "", 4000, "textureless"),
                                            madeRun("urban", "grid_random", "", 2000, "thin")})
                .status,
            "holds");
  EXPECT_EQ(check("urban_collision_kinds", {madeRun("urban", "monospheres", "", 4000, "textureless"),
                                            madeRun("urban", "grid_random", "", 2000, "textured")})
                .status,
            "undecided");  // 1 of 2 against the paper's 0 of 3: p = 0.4
  std::vector<ReportRun> textured;
  for (int k = 0; k < 3; ++k)
    textured.push_back(madeRun("urban", "monospheres", "", 4000, "textured")),
        textured.push_back(madeRun("urban", "grid_random", "", 2000, "textured"));
  EXPECT_EQ(check("urban_collision_kinds", textured).status, "fails");  // 6 of 6 against 0 of 3: p = 1 / 84
}

TEST(Findings, MonoSpheresUrbanCollisionsAfterTheMajorityOfTheBox) {
  EXPECT_EQ(check("urban_collisions_late", {madeRun("urban", "monospheres", "", 4000, "textureless", 0.7),
                                            madeRun("urban", "monospheres", "", 4000)})
                .status,
            "holds");
  const auto r = check("urban_collisions_late", {madeRun("urban", "monospheres", "", 4000, "textureless", 0.7),
                                                 madeRun("urban", "monospheres", "", 2000, "textureless", 0.3)});
  EXPECT_EQ(r.status, "undecided");
  EXPECT_EQ(r.measured,
            "2 collisions in 2 runs, box share at contact 0.70, 0.30; 1 early (rate 0.50 [0.09, 0.91]), exact test "
            "against the paper's p = 1.000");
}

TEST(Findings, CollisionsLateCountsTheMethodUnderThePublishedCodeToo) {
  ReportRun published = madeRun("urban", "monospheres", "", 4000, "textureless", 0.7);
  published.metrics["reference_code"] = {{"path_resend_8s", true}, {"pinhole_rays", true}};
  published.record = missionRecordOf(published.metrics, published.id + "/metrics.json").record;
  const auto r = check("urban_collisions_late", {published, madeRun("urban", "monospheres", "", 4000)});
  EXPECT_EQ(r.status, "holds");
  ReportRun ablated = madeRun("urban", "monospheres", "vpb", 4000, "textureless", 0.2);
  EXPECT_EQ(check("urban_collisions_late", {ablated}).status, "n/a");  // an ablation is not the method
}

TEST(Findings, TheMarkdownAndCsvCarryEveryFinding) {
  SweepResults s;
  s.axes = {"world", "method"};
  s.runs = joined({twoRuns("cave", "monospheres", "", 5000), twoRuns("cave", "grid_random", "", 2000)});
  const auto findings = evaluateFindings(s, reportRows(s));
  ASSERT_EQ(findings.size(), findingsTable().size());
  const std::string md = findingsMarkdown(findings), csv = findingsCsv(findings);
  EXPECT_NE(
      md.find("| ✓ holds | MonoSpheres covers at least twice the grid baseline's mean A in the cave | 5050 / 2020 = "
              "2.50 ["),
      std::string::npos)
      << md;
  EXPECT_NE(
      csv.find("ms_vs_grid_cave,\"MonoSpheres covers at least twice the grid baseline's mean A in the cave\",holds,"),
      std::string::npos)
      << csv;
  EXPECT_NE(csv.find("ms_vs_grid_urban,"), std::string::npos);
  EXPECT_NE(csv.find(",n/a,"), std::string::npos);
}

}  // namespace
}  // namespace msb
