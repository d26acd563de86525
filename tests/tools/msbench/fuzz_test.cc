// Seeded mutation fuzzing of the readers that take user files: flight and scenario YAML, world
// specs and perception logs. Each valid input is mutated a bounded number of times (byte flips,
// deletions, insertions of hostile tokens, truncation); every result must either load or be
// refused with one of the documented error types — never crash, hang or throw anything else.
// Under the sanitizer build (.ci/run) memory and undefined-behaviour errors abort the test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/rng.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/perception_log.h"
#include "tools/msbench/scenario_yaml.h"
#include "tools/msbench/world_registry.h"
#include "tools/msbench/yaml_config.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// One mutation of `text`, chosen by the stream.
std::string mutate(std::string text, RngStream& rng) {
  static const char* const kTokens[] = {"nan", "-inf", "1e308", "-1", "99999999999999999999", "[", "]", "{", "}",
                                        ":", "- ", "\n", "''", "~", "&a", "*a", "!!binary", "\t", "\0", ",,"};
  const int kinds = 5;
  const int rounds = 1 + int(rng.uniformInt(3));
  for (int r = 0; r < rounds && !text.empty(); ++r) {
    const size_t at = size_t(rng.uniformInt(text.size()));
    switch (int(rng.uniformInt(kinds))) {
      case 0: text[at] = char(rng.uniformInt(256)); break;                                    // flip a byte
      case 1: text.erase(at, 1 + size_t(rng.uniformInt(8))); break;                           // delete a run
      case 2: text.insert(at, kTokens[rng.uniformInt(sizeof(kTokens) / sizeof(*kTokens))]); break;  // hostile token
      case 3: text.resize(at); break;                                                           // truncate
      default: text.insert(at, text.substr(at, size_t(rng.uniformInt(32)))); break;            // repeat a run
    }
  }
  return text;
}

// Runs `load` on `n` mutations of `seed_text` written to `file`; only documented errors may escape.
template <class Load>
void fuzz(const std::string& seed_text, const fs::path& file, int n, const char* stream, Load load) {
  RngStream rng(11, stream);
  int loaded = 0, refused = 0;
  for (int i = 0; i < n; ++i) {
    const std::string input = mutate(seed_text, rng);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << input;
    try {
      load(file.string());
      ++loaded;
    } catch (const FileConfigError&) {
      ++refused;
    } catch (const ConfigError&) {
      ++refused;
    } catch (const UsageError&) {
      ++refused;
    } catch (const std::exception& e) {  // anything else (yaml-cpp's own, a bare runtime_error) is a defect
      ADD_FAILURE() << stream << " input " << i << ": unexpected " << typeid(e).name() << ": " << e.what()
                    << "\n--- input ---\n" << input;
    }
  }
  EXPECT_EQ(loaded + refused, n);
  EXPECT_GT(loaded, 0) << stream << ": no mutation loaded (is the seed input valid?)";
  EXPECT_GT(refused, n / 10) << stream << ": the mutations should break most inputs";
}

fs::path dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("msb_fuzz_" + name);
  fs::create_directories(d);
  fs::copy_file(fs::path(MSB_SOURCE_DIR) / "worlds/test/world.xml", d / "world.xml", fs::copy_options::overwrite_existing);
  return d;
}

TEST(Fuzz, FlightFiles) {
  const fs::path d = dir("flight");
  const std::string seed = "world: world.xml\nseed: 3\nduration_s: 5\nstart: {position: [0, 0, 0.05], yaw_deg: 10}\n"
                           "trajectory:\n  limits: medium\n  waypoints:\n    - [0, 0, 1.5]\n"
                           "    - {position: [5, 0, 1.5], heading_deg: 90}\ncamera: {scale: 0.5, k: [0.01, 0, 0, 0]}\n"
                           "camera_stream: {rate_hz: 15, save_every_n: 0}\nvio_drift: {position_drift_fraction: 0.01}\n";
  fuzz(seed, d / "f.yaml", 2000, "fuzz_flight", [](const std::string& p) { loadFlightSpec(p); });
}

TEST(Fuzz, ScenarioFiles) {
  const fs::path d = dir("scenario");
  const std::string seed = "world: world.xml\nseed: 2\nduration_s: 30\nmethod:\n  type: monospheres\n"
                           "  switches: {ovde: true, fff: false}\n  planner: {local_radius_m: 12, viewpoints: {min_value: 5}}\n"
                           "exploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\nmission: {map_rate_hz: 5}\n";
  fuzz(seed, d / "s.yaml", 2000, "fuzz_scenario", [](const std::string& p) { loadScenario(p); });
  const std::string grid = "world: world.xml\nmethod: {type: grid_random, replan_period_s: 0.5, map: {resolution_m: 0.5}}\n";
  fuzz(grid, d / "g.yaml", 500, "fuzz_grid", [](const std::string& p) { loadScenario(p); });
}

TEST(Fuzz, WorldSpecs) {
  const fs::path d = dir("world");
  const std::string seed = readFile(fs::path(MSB_SOURCE_DIR) / "worlds/sparse/spec.yaml");
  ASSERT_FALSE(seed.empty());
  fuzz(seed, d / "spec.yaml", 1000, "fuzz_world", [](const std::string& p) { loadWorldSpec(p); });
}

TEST(Fuzz, PerceptionLogs) {
  const fs::path d = dir("log");
  // A small valid log: three frames of a few points.
  {
    PerceptionLogWriter w((d / "seed.log").string(), nlohmann::json{{"camera_scale", 0.5}, {"world", "test"}});
    for (int f = 0; f < 3; ++f) {
      SlamPointsFrame frame;
      frame.tick = f * 33;
      frame.t_s = f / 15.0;
      for (int k = 0; k < 4; ++k) {
        SlamPoint p;
        p.track_id = uint64_t(k + 1);
        p.p_W = Vec3(3 + k, 0.5 * k, 1);
        p.depth_m = 3.0 + k;  // as the front end makes it: the reader checks contents
        p.anchor_tick = frame.tick;
        frame.points.push_back(p);
      }
      w.write(frame, Pose::Identity());
    }
    w.close();
  }
  fuzz(readFile(d / "seed.log"), d / "f.log", 2000, "fuzz_log", [](const std::string& p) { PerceptionLog::read(p); });
}

}  // namespace
}  // namespace msb

namespace msb {
namespace {

TEST(PerceptionLogFormat, AFlippedByteFailsTheChecksumOfItsFrame) {
  const fs::path d = dir("checksum");
  {
    PerceptionLogWriter w((d / "a.log").string(), nlohmann::json{{"camera_scale", 1}});
    for (int f = 0; f < 2; ++f) {
      SlamPointsFrame frame;
      frame.tick = f;
      SlamPoint p;
      p.track_id = 7;
      p.p_W = Vec3(1, 2, 3);
      p.depth_m = 3.7;  // a point as the front end makes it (the reader checks contents too)
      frame.points.push_back(p);
      w.write(frame, Pose::Identity());
    }
    w.close();
  }
  ASSERT_EQ(PerceptionLog::read((d / "a.log").string()).frames.size(), 2u);
  std::string bytes = readFile(d / "a.log");
  bytes[bytes.size() - 20] ^= 0x10;  // inside the last frame's payload
  std::ofstream(d / "b.log", std::ios::binary) << bytes;
  try {
    PerceptionLog::read((d / "b.log").string());
    FAIL() << "a corrupt frame was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("checksum mismatch in frame 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msb
