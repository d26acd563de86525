// The YAML layer: every error class names the file and the key, and valid files load fully.
#include "tools/config/flight_yaml.h"
#include "core/common/config_fields.h"
#include "tools/config/world_registry.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace msb {
namespace {

namespace fs = std::filesystem;

// A directory per test: ctest runs tests as parallel processes.
fs::path tempDir() {
  const fs::path d = fs::path(::testing::TempDir()) /
                     ("msb_yaml_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::create_directories(d);
  return d;
}

// Writes a flight file next to a copy of the test world; returns its path.
std::string writeFlight(const std::string& name, const std::string& text) {
  const fs::path dir = tempDir();
  fs::copy_file(fs::path(MSB_SOURCE_DIR) / "worlds/test/world.xml", dir / "world.xml",
                fs::copy_options::overwrite_existing);
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return file.string();
}

const char* kValid = R"(
world: world.xml
seed: 7
duration_s: 20
start: {position: [1, 2, 0.05], yaw_deg: 90}
trajectory:
  limits: fast
  waypoints:
    - [1, 2, 2]
    - {position: [5, 2, 2], heading_deg: 180}
camera: {scale: 0.5}
camera_stream: {rate_hz: 10, save_every_n: 0}
imu: {rate_hz: 250}
)";

// Expects loading to fail with a message containing the file name and every fragment.
void expectError(const std::string& text, std::initializer_list<std::string> fragments) {
  const std::string path = writeFlight("bad.yaml", text);
  try {
    loadFlightSpec(path);
    FAIL() << "expected FileConfigError for:\n" << text;
  } catch (const FileConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg << "\n  missing: " << f;
  }
}

TEST(YamlConfig, ValidFileLoadsWithRelativeWorldPath) {
  const FlightSpec s = loadFlightSpec(writeFlight("ok.yaml", kValid));
  EXPECT_EQ(s.world_path, (tempDir() / "world.xml").lexically_normal().string());
  EXPECT_EQ(s.seed, 7u);
  EXPECT_DOUBLE_EQ(s.start_yaw_rad, M_PI / 2);
  ASSERT_EQ(s.waypoints.size(), 2u);
  EXPECT_FALSE(s.waypoints[0].heading_rad);
  EXPECT_NEAR(*s.waypoints[1].heading_rad, M_PI, 1e-12);
  EXPECT_EQ(s.trajectory.limits.max_speed_mps, 8.0);
  EXPECT_EQ(s.camera.scale, 0.5);
  EXPECT_EQ(s.imu.rate_hz, 250.0);
  EXPECT_EQ(s.camera_stream.save_every_n, 0);
}

TEST(YamlConfig, UnknownKeyIsAnError) {
  expectError(std::string(kValid) + "colour: blue\n", {"colour", "unknown key"});
  expectError("world: world.xml\ntrajectory: {waypoints: [[0,0,1]], speeed: 3}\n",
              {"trajectory.speeed", "unknown key"});
  expectError("world: world.xml\ntrajectory: {waypoints: [{position: [0,0,1], heading: 3}]}\n",
              {"trajectory.waypoints[0].heading", "unknown key"});
}

TEST(YamlConfig, WrongTypeIsAnError) {
  expectError("world: world.xml\nduration_s: long\ntrajectory: {waypoints: [[0,0,1]]}\n",
              {"duration_s", "expected a number", "long"});
  expectError("world: world.xml\ntrajectory: {waypoints: [[0,0]]}\n",
              {"trajectory.waypoints[0]", "3 numbers, got a list of 2"});
  expectError("world: world.xml\ncamera: [1, 2]\ntrajectory: {waypoints: [[0,0,1]]}\n", {"camera", "expected a map"});
  expectError("world: world.xml\nseed: -3\ntrajectory: {waypoints: [[0,0,1]]}\n", {"seed", "non-negative integer"});
}

TEST(YamlConfig, MissingFilesAreErrors) {
  try {
    loadFlightSpec((tempDir() / "does_not_exist.yaml").string());
    FAIL();
  } catch (const FileConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.yaml: file not found"), std::string::npos);
  }
  expectError("world: no_such_world.xml\ntrajectory: {waypoints: [[0,0,1]]}\n",
              {"'world'", "file not found", "no_such_world.xml"});
}

TEST(YamlConfig, BadValuesAreErrors) {
  expectError("world: world.xml\ncamera: {scale: 0.3}\ntrajectory: {waypoints: [[0,0,1]]}\n",
              {"camera.scale", "must be 1, 0.5 or 0.25"});
  expectError("world: world.xml\ntrajectory: {limits: ludicrous, waypoints: [[0,0,1]]}\n",
              {"trajectory.limits", "unknown preset"});
  expectError("world: world.xml\ntrajectory: {limits: {max_speed_mps: -4}, waypoints: [[0,0,1]]}\n",
              {"trajectory.limits.max_speed_mps", "must be in"});
  expectError("world: world.xml\ncontroller_hz: 300\ntrajectory: {waypoints: [[0,0,1]]}\n",
              {"controller_hz", "must divide"});
  expectError("world: world.xml\n", {"trajectory.waypoints", "at least one"});
}

TEST(YamlConfig, SyntaxErrorNamesTheLine) {
  expectError("world: world.xml\ntrajectory: {waypoints: [[0,0,1]]\n", {"YAML syntax error", "line"});
}

TEST(YamlConfig, WorldSpecErrorsNameFileAndKey) {
  const fs::path dir = tempDir();
  auto expect = [&](const std::string& text, const std::string& fragment) {
    std::ofstream(dir / "spec.yaml") << text;
    try {
      loadWorldSpec((dir / "spec.yaml").string());
      FAIL() << text;
    } catch (const FileConfigError& e) {
      EXPECT_NE(std::string(e.what()).find((dir / "spec.yaml").string()), std::string::npos);
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const std::string base = "name: w\nexploration_box: {min: [0, 0, 0], max: [10, 10, 5]}\n";
  expect(base + "objects: [{kind: tree, at: [1, 1], size: [3, 0, 6], colour: red}]\n", "objects[0].colour");
  expect(base + "objects: [{kind: dragon, at: [1, 1], size: [3, 0, 6]}]\n", "unknown object kind");
  expect(base + "ground: {texture: marble}\n", "ground.texture");
  expect(base + "objects: [{kind: tree, size: [3, 0, 6]}]\n", "either 'at' or 'region'");
  expect("name: w\nexploration_box: {min: [0, 0, 0], max: [10, 10, -5]}\n", "exploration_box");
  // The shipped specs load.
  for (const char* w : {"urban", "cave", "rooftops", "sparse"})
    EXPECT_NO_THROW(loadWorldSpec(std::string(MSB_SOURCE_DIR) + "/worlds/" + w + "/spec.yaml")) << w;
}

// Collects a key table's keys with a YAML value each refuses ("" when none of its type is).
struct TableKeys {
  std::vector<std::pair<std::string, std::string>> keys;
  template <class T>
  void key(const char* name, T&) {
    keys.push_back({name, ""});
  }
  void key(const char* name, std::string&, const Choices& c) { keys.push_back({name, c.outside()}); }
  template <class T>
  void key(const char* name, T&, const Limits& l) {
    const double v = l.outside();
    std::ostringstream os;
    os << v;  // shortest form: "0", "-1", "127", "-0.5" (an integer key reads it as an integer)
    std::string text = std::isnan(v) ? "" : os.str();
    if constexpr (std::is_same_v<T, Vec2>) text = text.empty() ? "" : "[" + text + ", " + text + "]";
    if constexpr (std::is_same_v<T, Vec3>) text = text.empty() ? "" : "[" + text + ", " + text + ", " + text + "]";
    keys.push_back({name, text});
  }
};

template <class Spec>
std::vector<std::pair<std::string, std::string>> tableKeys() {
  Spec spec;
  TableKeys t;
  Spec::fields(spec, t);
  return t.keys;
}

// Every key of the world specs' tables is documented in docs/worlds.md and refuses a value
// outside its rule through the real reader, naming the key.
TEST(YamlConfig, EveryWorldSpecKeyIsDocumentedAndChecked) {
  std::ifstream in(fs::path(MSB_SOURCE_DIR) / "docs/worlds.md");
  const std::string docs((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path dir = tempDir();
  const std::string cave =
      "cave: {min: [-20, -20], max: [20, 20], chambers: [{min: [-5, -5], max: [5, 5]}], "
      "tunnels: [{from: [0, 0], to: [10, 0]}]}\n";
  const std::string base = "name: w\nexploration_box: {min: [0, 0, 0], max: [10, 10, 5]}\n";
  const std::string object = "objects: [{kind: rock, at: [1, 1], size: [1, 1, 1]}]\n";
  const std::string meshes = "source: {repository: a/b, commit: c0ffee}\nmeshes: [{file: m/terrain.dae}]\n";
  std::ofstream(dir / "spec.yaml") << base << object << cave << meshes;
  ASSERT_NO_THROW(loadWorldSpec((dir / "spec.yaml").string()));
  int probed = 0;
  // (a table, how a value of one of its keys is put into the spec)
  const std::vector<std::pair<std::vector<std::pair<std::string, std::string>>, std::string>> tables = {
      {tableKeys<WorldSpec>(), ""},
      {tableKeys<ObjectGroupSpec>(), "objects[0]."},
      {tableKeys<CaveSpec>(), "cave."},
      {tableKeys<CaveChamberSpec>(), "cave.chambers[0]."},
      {tableKeys<CaveTunnelSpec>(), "cave.tunnels[0]."},
      {tableKeys<SourceSpec>(), "source."},
      {tableKeys<MeshSpec>(), "meshes[0]."}};
  for (const auto& [keys, prefix] : tables) {
    for (const auto& [name, refused] : keys) {
      EXPECT_NE(docs.find(name), std::string::npos) << prefix << name << " is not in docs/worlds.md";
      if (refused.empty()) continue;
      YAML::Node spec = YAML::LoadFile((dir / "spec.yaml").string());
      YAML::Node at = prefix.empty()                  ? spec
                      : prefix == "objects[0]."       ? spec["objects"][0]
                      : prefix == "cave."             ? spec["cave"]
                      : prefix == "cave.chambers[0]." ? spec["cave"]["chambers"][0]
                      : prefix == "source."           ? spec["source"]
                      : prefix == "meshes[0]."        ? spec["meshes"][0]
                                                      : spec["cave"]["tunnels"][0];
      at[name] = YAML::Load(refused);
      YAML::Emitter e;
      e << spec;
      std::ofstream(dir / "probe.yaml") << e.c_str();
      try {
        loadWorldSpec((dir / "probe.yaml").string());
        ADD_FAILURE() << prefix << name << ": " << refused << " was accepted";
      } catch (const FileConfigError& err) {
        EXPECT_NE(std::string(err.what()).find(prefix + name), std::string::npos) << err.what();
      }
      ++probed;
    }
  }
  EXPECT_GE(probed, 22);
}

}  // namespace
}  // namespace msb
