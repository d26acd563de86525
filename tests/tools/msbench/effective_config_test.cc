// The effective configuration (config.yaml of every run): every method in the method registry
// writes all its keys, defaults included, and `msbench run OUT/config.yaml` reproduces the
// run's determinism hash. The example method hover_turn flies its take-off, turn and descent.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"
#include "tools/config/method_table.h"

namespace {

namespace fs = std::filesystem;

using msb_test::readText;
using msb_test::run;

// A short mission of `type` in the test yard.
fs::path writeScenario(const fs::path& dir, const std::string& type, double duration_s) {
  const fs::path p = dir / (type + ".yaml");
  std::ofstream(p) << "world: " << MSB_SOURCE_DIR << "/worlds/test/world.xml\n"
                   << "start: {position: [0, 0, 0.05], yaw_deg: 30}\n"
                   << "exploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\n"
                   << "duration_s: " << duration_s << "\nmethod: {type: " << type;
  // A Python method: the example method's twin (run by the Python module).
  if (type == "python")
    std::ofstream(p, std::ios::app) << ", entry: \"hover_turn:factory\", path: " << MSB_SOURCE_DIR
                                    << "/examples/python";
  std::ofstream(p, std::ios::app) << "}\n";
  return p;
}

nlohmann::json metrics(const fs::path& out) { return nlohmann::json::parse(readText(out / "metrics.json")); }

TEST(EffectiveConfig, RunningAConfigYamlReproducesTheRunForEveryMethod) {
  for (const msb::MethodRegistration& reg : msb::methodRegistrations()) {
    const msb::MethodInfo& method = reg.info;
    SCOPED_TRACE(method.type);
#ifndef MSB_HAS_PYTHON_MODULE
    if (method.type == "python") continue;  // the module is not built (no pybind11)
#endif
    const fs::path d = msb_test::tempDir("msb_effective_", method.type);
    const fs::path scenario = writeScenario(d, method.type, 12.0);
    ASSERT_EQ(run("run '" + scenario.string() + "' --quiet --out '" + (d / "a").string() + "'", d / "log_a"), 0)
        << readText(d / "log_a");
    const std::string config = readText(d / "a" / "config.yaml");
    // Every key with its value: the defaults the scenario did not name are there.
    EXPECT_NE(config.find("slam_points:"), std::string::npos);
    EXPECT_NE(config.find("physics_hz:"), std::string::npos);
    EXPECT_NE(config.find("metric_rate_hz:"), std::string::npos);
    EXPECT_NE(config.find("type: " + method.type), std::string::npos);
    ASSERT_EQ(
        run("run '" + (d / "a" / "config.yaml").string() + "' --quiet --out '" + (d / "b").string() + "'", d / "log_b"),
        0)
        << readText(d / "log_b");
    const auto a = metrics(d / "a"), b = metrics(d / "b");
    EXPECT_EQ(a["status"], "completed");
    EXPECT_EQ(a["determinism_hash"], b["determinism_hash"]);
    // Written again from the re-read configuration: the same text (a fixed point).
    // (After the first line, which names the file it came from.)
    const std::string again = readText(d / "b" / "config.yaml");
    EXPECT_EQ(again.substr(again.find('\n')), config.substr(config.find('\n')));
  }
}

TEST(EffectiveConfig, TheExampleMethodTakesOffTurnsAndDescends) {
  const fs::path d = msb_test::tempDir("msb_effective_", "hover_turn_flight");
  const fs::path scenario = writeScenario(d, "hover_turn", 40.0);
  ASSERT_EQ(run("run '" + scenario.string() + "' --quiet --out '" + (d / "a").string() + "'", d / "log"), 0)
      << readText(d / "log");
  const auto m = metrics(d / "a");
  EXPECT_EQ(m["status"], "completed") << m.dump(2);
  EXPECT_EQ(m["counters"]["turn_steps"].get<double>(), 8.0);  // 360° in 45° steps
  EXPECT_GT(m["counters"]["points_seen"].get<double>(), 100.0);
  // Its one free-space sphere (bounded by the ground points 2 m below) scores the columns
  // around the start, not the yard.
  const double area = m["coverage"]["area_box_m2"].get<double>();
  EXPECT_GE(area, 6.25);
  EXPECT_LT(area, 100.0);
  // It ends low above the start: the last trajectory row (t, x, y, z, ...) near (0, 0, 0.35).
  const std::string traj = readText(d / "a" / "trajectory.csv");
  const std::string last = traj.substr(traj.rfind('\n', traj.size() - 2) + 1);
  double t, x, y, z;
  ASSERT_EQ(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf", &t, &x, &y, &z), 4) << last;
  EXPECT_NEAR(t, 39.9, 0.2);
  EXPECT_LT(std::hypot(x, y), 0.3);
  EXPECT_NEAR(z, 0.35, 0.1);
}

}  // namespace
