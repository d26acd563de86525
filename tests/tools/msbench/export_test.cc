// msbench export: a grid-baseline run leaves its OctoMap as map.bt, which liboctomap loads back
// with the run's leaf count; `export` turns trajectory.csv into TUM files of 8 columns whose
// numbers are trajectory.csv's, and refuses a directory that is not a run, writing nothing.
#include <gtest/gtest.h>

#include <octomap/octomap.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"

namespace {

namespace fs = std::filesystem;

using msb_test::readText;
using msb_test::run;

// The lines of `text` that are not comments, split at spaces.
std::vector<std::vector<std::string>> tumRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream c(line);
    for (std::string cell; c >> cell;) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(Export, AGridRunsMapBtLoadsAndItsTrajectoriesBecomeTumFiles) {
  const fs::path d = msb_test::tempDir("msb_export_", "grid");
  std::ofstream(d / "grid.yaml") << "world: " << MSB_SOURCE_DIR << "/worlds/test/world.xml\n"
                                 << "start: {position: [0, 0, 0.05], yaw_deg: 30}\n"
                                 << "exploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\n"
                                 << "duration_s: 12\nmethod: {type: grid_random}\n";
  ASSERT_EQ(run("run '" + (d / "grid.yaml").string() + "' --quiet --out '" + (d / "run").string() + "'", d / "log"), 0)
      << readText(d / "log");
  // map.bt: liboctomap's own reader, the run's leaf count.
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary((d / "run" / "map.bt").string()));
  const auto metrics = nlohmann::json::parse(readText(d / "run" / "metrics.json"));
  EXPECT_GT(tree.getNumLeafNodes(), 100u);
  EXPECT_EQ(double(tree.getNumLeafNodes()), metrics["counters"]["leaves"].get<double>());
  EXPECT_EQ(tree.getResolution(), 0.5);

  ASSERT_EQ(run("export '" + (d / "run").string() + "' --out '" + (d / "x").string() + "'", d / "log_x"), 0)
      << readText(d / "log_x");
  const auto truth = tumRows(readText(d / "x" / "truth.tum"));
  const auto estimate = tumRows(readText(d / "x" / "estimate.tum"));
  EXPECT_TRUE(fs::exists(d / "x" / "map.bt"));
  // Each TUM row is the trajectory.csv row's numbers, as written there (the quaternion w last).
  std::istringstream csv(readText(d / "run" / "trajectory.csv"));
  std::string line;
  std::getline(csv, line);
  size_t i = 0;
  for (; std::getline(csv, line); ++i) {
    std::vector<std::string> c;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) c.push_back(cell);
    ASSERT_EQ(c.size(), 23u);
    ASSERT_LT(i, truth.size());
    ASSERT_EQ(truth[i].size(), 8u);
    ASSERT_EQ(estimate[i].size(), 8u);
    EXPECT_EQ(truth[i], (std::vector<std::string>{c[0], c[1], c[2], c[3], c[5], c[6], c[7], c[4]}));
    EXPECT_EQ(estimate[i], (std::vector<std::string>{c[0], c[11], c[12], c[13], c[20], c[21], c[22], c[19]}));
  }
  EXPECT_EQ(i, truth.size());
  EXPECT_GT(i, 100u);
  const auto info = nlohmann::json::parse(readText(d / "x" / "export.json"));
  EXPECT_EQ(info["poses"].get<size_t>(), i);

  // Not a run: exit 2 naming it, nothing written.
  fs::create_directories(d / "not_a_run");
  EXPECT_EQ(run("export '" + (d / "not_a_run").string() + "' --out '" + (d / "y").string() + "'", d / "log_y"), 2);
  EXPECT_NE(readText(d / "log_y").find("not a run directory"), std::string::npos) << readText(d / "log_y");
  EXPECT_FALSE(fs::exists(d / "y"));
}

}  // namespace
