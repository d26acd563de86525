// Seeded mutation fuzzing of the YAML readers: flight and scenario files, world specs
// (tests/tools/fuzz_helpers.h: every mutation loads or is refused with a documented error).
#include <gtest/gtest.h>

#include "tests/tools/fuzz_helpers.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"

namespace msb {
namespace {

using namespace fuzz_test;

TEST(Fuzz, FlightFiles) {
  const fs::path d = dir("flight");
  const std::string seed =
      "world: world.xml\nseed: 3\nduration_s: 5\nstart: {position: [0, 0, 0.05], yaw_deg: 10}\n"
      "trajectory:\n  limits: medium\n  waypoints:\n    - [0, 0, 1.5]\n"
      "    - {position: [5, 0, 1.5], heading_deg: 90}\ncamera: {scale: 0.5, k: [0.01, 0, 0, 0]}\n"
      "camera_stream: {rate_hz: 15, save_every_n: 0}\nvio_drift: {position_drift_fraction: 0.01}\n";
  fuzz(seed, d / "f.yaml", 2000, "fuzz_flight", [](const std::string& p) { loadFlightSpec(p); });
}

TEST(Fuzz, ScenarioFiles) {
  const fs::path d = dir("scenario");
  const std::string seed =
      "world: world.xml\nseed: 2\nduration_s: 30\nmethod:\n  type: monospheres\n"
      "  switches: {ovde: true, fff: false}\n  planner: {local_radius_m: 12, viewpoints: {min_value: 5}}\n"
      "exploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\nmission: {map_rate_hz: 5}\n";
  fuzz(seed, d / "s.yaml", 2000, "fuzz_scenario", [](const std::string& p) { loadScenario(p); });
  const std::string grid =
      "world: world.xml\nmethod: {type: grid_random, replan_period_s: 0.5, map: {resolution_m: 0.5}}\n";
  fuzz(grid, d / "g.yaml", 500, "fuzz_grid", [](const std::string& p) { loadScenario(p); });
}

TEST(Fuzz, WorldSpecs) {
  const fs::path d = dir("world");
  const std::string seed = readFile(fs::path(MSB_SOURCE_DIR) / "worlds/sparse/spec.yaml");
  ASSERT_FALSE(seed.empty());
  fuzz(seed, d / "spec.yaml", 1000, "fuzz_world", [](const std::string& p) { loadWorldSpec(p); });
}

}  // namespace
}  // namespace msb
