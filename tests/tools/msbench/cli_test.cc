// The msbench executable end to end: exit codes, nothing written on bad input, determinism.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"

namespace {

namespace fs = std::filesystem;

using msb_test::kExe;
using msb_test::readText;
using msb_test::run;

fs::path tempDir(const std::string& name) { return msb_test::tempDir("msb_cli_", name); }

TEST(Cli, HelpAndUsageErrors) {
  const fs::path d = tempDir("help");
  EXPECT_EQ(run("--help", d / "log"), 0);
  EXPECT_NE(readText(d / "log").find("render-probe"), std::string::npos);
  for (const char* c : {"fly --help", "render-probe --help", "bench-sim --help"}) {
    EXPECT_EQ(run(c, d / "log"), 0) << c;
    EXPECT_NE(readText(d / "log").find("usage: msbench"), std::string::npos) << c;
  }
  EXPECT_EQ(run("", d / "log"), 2);
  EXPECT_EQ(run("teleport", d / "log"), 2);
  EXPECT_EQ(run("render-probe --out x.png --bogus 1", d / "log"), 2);
  EXPECT_NE(readText(d / "log").find("unknown option --bogus"), std::string::npos);
  EXPECT_EQ(run("render-probe --out x.png --pose 1,2", d / "log"), 2);
  EXPECT_EQ(run("render-probe --out x.png --world nowhere", d / "log"), 2);
  EXPECT_NE(readText(d / "log").find(
                "available: burned_probe, cave, lushcave, rooftops, sparse, sparse1, suburb3, test, urban"),
            std::string::npos)
      << readText(d / "log");
}

// msbench methods lists every registered method; a method's keys, as printed, are a method:
// section a scenario accepts (the same effective configuration back).
TEST(Cli, MethodsListsEveryMethodAndKeysAScenarioAccepts) {
  const fs::path d = tempDir("methods");
  ASSERT_EQ(run("methods", d / "list"), 0) << readText(d / "list");
  for (const char* type : {"monospheres:", "grid_random:", "star_discovery:", "hover_turn:", "python:"})
    EXPECT_NE(readText(d / "list").find(type), std::string::npos) << type;
  ASSERT_EQ(run("methods --type monospheres", d / "mono"), 0) << readText(d / "mono");
  const std::string mono = readText(d / "mono");
  EXPECT_NE(mono.find("ovde: true"), std::string::npos) << mono;
  // The keys block, unindented, as a scenario's method section over the short test mission.
  std::istringstream in(mono.substr(mono.find("    method:")));
  std::string line, section;
  while (std::getline(in, line)) section += line.substr(4) + "\n";
  std::ofstream(d / "s.yaml") << "base: " << MSB_SOURCE_DIR << "/scenarios/missions/test_world_short.yaml\n" << section;
  ASSERT_EQ(
      run("run '" + (d / "s.yaml").string() + "' --duration 1 --quiet --out '" + (d / "o").string() + "'", d / "run"),
      0)
      << readText(d / "run");
  EXPECT_NE(readText(d / "o" / "config.yaml").find("ovde: true"), std::string::npos);
  EXPECT_EQ(run("methods --type nope", d / "nope"), 2);
  EXPECT_NE(readText(d / "nope").find("known: monospheres"), std::string::npos) << readText(d / "nope");
}

TEST(Cli, WorldListBuildAndShow) {
  const fs::path d = tempDir("world");
  const std::string env = "MSBENCH_CACHE_DIR='" + (d / "cache").string() + "' ";
  EXPECT_EQ(run("world list", d / "log"), 0);
  for (const char* w : {"urban", "cave", "rooftops", "sparse", "test"})
    EXPECT_NE(readText(d / "log").find(w), std::string::npos) << w;
  // build: prints where and what; a second build reuses the cache.
  ASSERT_EQ(std::system((env + "'" + kExe + "' world build sparse > '" + (d / "b1").string() + "'").c_str()), 0);
  EXPECT_NE(readText(d / "b1").find("(built)"), std::string::npos) << readText(d / "b1");
  ASSERT_EQ(std::system((env + "'" + kExe + "' world build sparse > '" + (d / "b2").string() + "'").c_str()), 0);
  EXPECT_NE(readText(d / "b2").find("(cached)"), std::string::npos);
  // show: top-down map, views and a summary with the explorable columns.
  ASSERT_EQ(std::system((env + "'" + kExe + "' world show sparse --out '" + (d / "show").string() + "' > '" +
                         (d / "b3").string() + "'")
                            .c_str()),
            0);
  for (const char* f : {"topdown.png", "views.png", "summary.json"})
    EXPECT_TRUE(fs::is_regular_file(d / "show" / f)) << f;
  const auto j = nlohmann::json::parse(readText(d / "show" / "summary.json"));
  EXPECT_GT(j["explorable_columns"].get<int>(), 100);
  EXPECT_EQ(run("world build nowhere", d / "log"), 2);
  EXPECT_EQ(run("world build test", d / "log"), 2);  // hand-written, not generated
}

TEST(Cli, BadFlightFileExitsWith2AndWritesNothing) {
  const fs::path d = tempDir("bad");
  std::ofstream(d / "bad.yaml") << "world: ../../nowhere.xml\nwaypointz: []\n";
  EXPECT_EQ(run("fly '" + (d / "bad.yaml").string() + "' --out '" + (d / "out").string() + "'", d / "log"), 2);
  const std::string log = readText(d / "log");
  EXPECT_NE(log.find("bad.yaml"), std::string::npos) << log;
  EXPECT_NE(log.find("waypointz"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(d / "out"));
  EXPECT_FALSE(fs::exists(d / "out.partial"));
}

TEST(Cli, ExistingResultsAreNotOverwritten) {
  const fs::path d = tempDir("exists");
  fs::create_directories(d / "out");
  std::ofstream(d / "out" / "metrics.json") << "{}";
  std::ofstream(d / "f.yaml") << "world: " << MSB_SOURCE_DIR
                              << "/worlds/test/world.xml\nduration_s: 0.1\n"
                                 "trajectory: {waypoints: [[0,0,1]]}\n";
  EXPECT_EQ(run("fly '" + (d / "f.yaml").string() + "' --out '" + (d / "out").string() + "'", d / "log"),
            2);  // a usage error: the output directory is taken
  EXPECT_EQ(readText(d / "out" / "metrics.json"), "{}");
}

TEST(Cli, FlyTwiceGivesIdenticalTrajectoriesAndAllOutputs) {
  const fs::path d = tempDir("fly");
  std::ofstream(d / "f.yaml") << "world: " << MSB_SOURCE_DIR << "/worlds/test/world.xml\n"
                              << "duration_s: 8\nseed: 3\n"
                                 "trajectory:\n  waypoints: [[0,0,1.5], [5,0,1.5], [5,4,2]]\n"
                                 "camera: {scale: 0.5}\n"
                                 "camera_stream: {rate_hz: 10, save_every_n: 20}\n";
  std::string hashes[2];
  for (int i = 0; i < 2; ++i) {
    const fs::path out = d / ("run" + std::to_string(i));
    ASSERT_EQ(run("fly '" + (d / "f.yaml").string() + "' --out '" + out.string() + "'", d / "log"), 0)
        << readText(d / "log");
    for (const char* f : {"metrics.json", "trajectory.csv", "imu.csv", "config.yaml"})
      EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
    EXPECT_TRUE(fs::is_regular_file(out / "frames" / "frame_000000_t0000.00.png"));
    const auto m = nlohmann::json::parse(readText(out / "metrics.json"));
    EXPECT_EQ(m["status"], "completed");
    EXPECT_EQ(m["frames_rendered"], 80);  // t = 0, 0.1, ..., 7.9 s
    EXPECT_GT(m["real_time_factor"].get<double>(), 0.0);
    hashes[i] = m["trajectory_hash"];
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(readText(d / "run0" / "trajectory.csv"), readText(d / "run1" / "trajectory.csv"));
  EXPECT_EQ(readText(d / "run0" / "imu.csv"), readText(d / "run1" / "imu.csv"));
  EXPECT_EQ(readText(d / "run0" / "frames" / "frame_000060_t0006.00.png"),
            readText(d / "run1" / "frames" / "frame_000060_t0006.00.png"));
}

}  // namespace
