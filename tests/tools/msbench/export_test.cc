// msbench export: a grid-baseline run leaves its OctoMap as map.bt, which liboctomap loads back
// with the run's leaf count; `export` turns trajectory.csv into TUM files of 8 columns whose
// numbers are trajectory.csv's, and refuses a directory that is not a run, writing nothing.
#include <gtest/gtest.h>

#include <octomap/octomap.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "core/geometry/world_truth.h"
#include "tests/tools/cli_helpers.h"
#include "tools/config/world_registry.h"

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

// The ns stamps of an EuRoC data.csv (first cell of each non-comment line) and its cells.
std::vector<std::vector<std::string>> csvRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream c(line);
    for (std::string cell; std::getline(c, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(Export, EurocReplaysTheRunIntoOnePngPerFrameAtMonotonicNanosecondStamps) {
  const fs::path d = msb_test::tempDir("msb_export_", "euroc");
  std::ofstream(d / "ms.yaml") << "world: " << MSB_SOURCE_DIR << "/worlds/test/world.xml\n"
                               << "start: {position: [0, 0, 0.05], yaw_deg: 30}\n"
                               << "exploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\n"
                               << "duration_s: 4\ncamera: {scale: 0.5}\n";
  ASSERT_EQ(run("run '" + (d / "ms.yaml").string() + "' --quiet --out '" + (d / "run").string() + "'", d / "log"), 0)
      << readText(d / "log");
  ASSERT_EQ(
      run("export '" + (d / "run").string() + "' --euroc --quiet --out '" + (d / "x").string() + "'", d / "log_x"), 0)
      << readText(d / "log_x");
  const fs::path mav = d / "x" / "mav0";
  // One PNG per frame row, named by its stamp; stamps strictly increasing; 15 Hz for 4 s.
  const auto frames = csvRows(readText(mav / "cam0" / "data.csv"));
  EXPECT_GE(frames.size(), 59u);
  EXPECT_LE(frames.size(), 61u);
  long long last = -1;
  for (const auto& f : frames) {
    ASSERT_EQ(f.size(), 2u);
    EXPECT_GT(std::stoll(f[0]), last);
    last = std::stoll(f[0]);
    EXPECT_EQ(f[1], f[0] + ".png");
    EXPECT_TRUE(fs::is_regular_file(mav / "cam0" / "data" / f[1])) << f[1];
  }
  size_t pngs = 0;
  for (const auto& e : fs::directory_iterator(mav / "cam0" / "data")) pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, frames.size());
  // The IMU at 200 Hz, 7 cells, increasing; the ground truth one row per trajectory.csv row.
  const auto imu = csvRows(readText(mav / "imu0" / "data.csv"));
  EXPECT_GE(imu.size(), 790u);
  last = -1;
  for (const auto& m : imu) {
    ASSERT_EQ(m.size(), 7u);
    EXPECT_GT(std::stoll(m[0]), last);
    last = std::stoll(m[0]);
  }
  const auto gt = csvRows(readText(mav / "state_groundtruth_estimate0" / "data.csv"));
  const auto traj = csvRows(readText(d / "run" / "trajectory.csv"));
  ASSERT_EQ(gt.size() + 1, traj.size());  // trajectory.csv's header has no '#'
  for (size_t i = 0; i < gt.size(); ++i) {
    ASSERT_EQ(gt[i].size(), 11u);
    EXPECT_EQ(std::vector<std::string>(gt[i].begin() + 1, gt[i].end()),
              std::vector<std::string>(traj[i + 1].begin() + 1, traj[i + 1].begin() + 11));
  }
  for (const char* f : {"camchain.yaml", "imu.yaml", "camera_info.yaml", "truth.tum"})
    EXPECT_TRUE(fs::is_regular_file(d / "x" / f)) << f;
  const auto info = nlohmann::json::parse(readText(d / "x" / "export.json"));
  EXPECT_EQ(info["frames"].get<size_t>(), frames.size());
  // The map in both frames, as many vertices as map.ply, each header naming its frame.
  const std::string ply = readText(d / "run" / "map.ply");
  const std::string n = ply.substr(ply.find("element vertex "),
                                   ply.find('\n', ply.find("element vertex ")) - ply.find("element vertex "));
  for (const char* f : {"map_odom.ply", "map_world.ply"}) {
    const std::string out = readText(d / "x" / f);
    EXPECT_NE(out.find(n + "\n"), std::string::npos) << f << " " << n;
    EXPECT_NE(out.find(std::string("frame_id ") + (f == std::string("map_odom.ply") ? "odom" : "map")),
              std::string::npos);
  }
  EXPECT_GT(info["map"]["free_space"].get<int>(), 10);

  // A run whose config.yaml no longer replays it (duration changed after the run): the replay's
  // hash is not the recorded one; exit 1 and no export directory.
  fs::copy(d / "run", d / "edited", fs::copy_options::recursive);
  std::string config = readText(d / "edited" / "config.yaml");
  ASSERT_NE(config.find("duration_s: 4"), std::string::npos) << config;
  config.replace(config.find("duration_s: 4"), 13, "duration_s: 3");
  std::ofstream(d / "edited" / "config.yaml") << config;
  EXPECT_EQ(
      run("export '" + (d / "edited").string() + "' --euroc --quiet --out '" + (d / "z").string() + "'", d / "log_z"),
      1);
  EXPECT_NE(readText(d / "log_z").find("not the recorded run"), std::string::npos) << readText(d / "log_z");
  EXPECT_FALSE(fs::exists(d / "z"));
}

// The float x y z of each vertex of a binary PLY whose vertices are `stride` bytes.
std::vector<msb::Vec3> plyPoints(const std::string& ply, size_t stride) {
  const size_t n_at = ply.find("element vertex ") + 15;
  const size_t n = std::stoul(ply.substr(n_at, ply.find('\n', n_at) - n_at));
  const size_t body = ply.find("end_header\n") + 11;
  std::vector<msb::Vec3> out;
  for (size_t i = 0; i < n; ++i) {
    float f[3];
    std::memcpy(f, ply.data() + body + i * stride, 12);
    out.emplace_back(f[0], f[1], f[2]);
  }
  return out;
}

TEST(WorldExport, TheMeshLoadsInAssimpAndEveryCloudPointLiesOnTheTruthNoSaltReachingIt) {
  const fs::path d = msb_test::tempDir("msb_export_", "world");
  ASSERT_EQ(run("world export sparse --out '" + (d / "w").string() + "'", d / "log"), 0) << readText(d / "log");
  const auto info = nlohmann::json::parse(readText(d / "w" / "world_export.json"));
  // assimp, an independent PLY reader, finds the triangles the export says it wrote.
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((d / "w" / "truth_mesh.ply").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  EXPECT_EQ(scene->mMeshes[0]->mNumFaces, info["triangles"].get<unsigned>());
  EXPECT_GT(info["triangles"].get<unsigned>(), 1000u);
  // Each sampled point is on a shape's surface (round shapes are 32-gons: chord error ≤ 0.5 % of
  // the radius) and the cloud has the density asked for.
  const msb::ResolvedWorld world = msb::resolveWorld("sparse");
  const msb::WorldTruth truth(world.built->generated.shapes);
  const auto points = plyPoints(readText(d / "w" / "truth_points.ply"), 12 + 4);
  EXPECT_EQ(points.size(), info["points"].get<size_t>());
  EXPECT_GT(points.size(), 10000u);
  double worst = 0;
  for (size_t i = 0; i < points.size(); i += 7) worst = std::max(worst, std::abs(truth.distance(points[i], 5.0)));
  EXPECT_LT(worst, 0.03);
  // The evaluator's salt changes nothing: the export is the public spec's world.
  ASSERT_EQ(run("world export sparse --out '" + (d / "w2").string() + "'", d / "log2"), 0);
  ASSERT_EQ(std::system(("MSBENCH_WORLD_SALT=0123456789abcdef0123 '" + msb_test::kExe +
                         "' world export sparse --out '" + (d / "w3").string() + "' > /dev/null 2>&1")
                            .c_str()),
            0);
  EXPECT_EQ(readText(d / "w" / "truth_points.ply"), readText(d / "w3" / "truth_points.ply"));
  EXPECT_EQ(readText(d / "w" / "truth_mesh.ply"), readText(d / "w2" / "truth_mesh.ply"));
}

}  // namespace
