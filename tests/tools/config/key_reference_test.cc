// The key reference (`msbench keys`, docs/keys.md): current, complete, and true — every key the
// reader accepts is listed with what it accepts, every number has a rule, and every rule refuses
// a value outside it through the real scenario reader, naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "tools/config/key_reference.h"
#include "tools/config/scenario_yaml.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(KeyReference, TheDocsFileIsCurrent) {
  EXPECT_EQ(readFile(fs::path(MSB_SOURCE_DIR) / "docs/keys.md"), keyReferenceMarkdown())
      << "docs/keys.md is out of date: regenerate it with `msbench keys > docs/keys.md`";
}

TEST(KeyReference, ListsTheKeysOfEverySectionAndEveryMethod) {
  std::set<std::string> keys, sections;
  for (const KeyRow& r : keyReference()) {
    keys.insert(r.key);
    sections.insert(r.section);
  }
  for (const char* k :
       {"duration_s", "physics.vehicle.mass_kg", "trajectory.limits.max_speed_mps", "camera.fx_px",
        "conditions.fog_end_m", "frontend.mistrack_px", "perception.oracle.max_tracks", "mission.map_rate_hz",
        "video.fps", "method.map.ovde_params.grid", "method.planner.safety.r_safe_m", "method.planner.check_ahead_m",
        "method.switches.ovde", "method.reference_code.path_resend_8s", "method.goal_period_s", "method.turn_step_deg",
        "method.call_budget_s", "world", "exploration_box.min"})
    EXPECT_TRUE(keys.count(k)) << k;
  for (const char* s : {"scenario", "method.type: monospheres", "method.type: grid_random",
                        "method.type: star_discovery", "method.type: hover_turn", "method.type: python"})
    EXPECT_TRUE(sections.count(s)) << s;
}

// Every number written from a key table carries its rule: a key without one is unvalidated.
TEST(KeyReference, EveryNumberHasARule) {
  for (const KeyRow& r : keyReference())
    EXPECT_FALSE(r.accepts.empty()) << r.section << ": " << r.key << " (default " << r.default_value
                                    << ") has no rule in its key table";
}

// Each rule, through the real reader: the value just outside it is refused, naming the key.
TEST(KeyReference, EveryKeyRefusesAValueOutsideWhatItAccepts) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_key_reference";
  fs::create_directories(d);
  std::ofstream(d / "s.yaml") << "world: urban\n";
  int probed = 0;
  for (const KeyRow& r : keyReference()) {
    if (r.refused_value.empty()) continue;
    std::vector<std::string> sets;
    if (r.section.rfind("method.type: ", 0) == 0) {
      const std::string type = r.section.substr(13);
      sets.push_back("method.type=" + type);
      if (type == "python") sets.push_back("method.entry=m:f");
    }
    sets.push_back(r.key + "=" + r.refused_value);
    try {
      loadScenario((d / "s.yaml").string(), sets);
      ADD_FAILURE() << r.key << "=" << r.refused_value << " was accepted (rule: " << r.accepts << ")";
    } catch (const FileConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + r.key + "'"), std::string::npos)
          << r.key << "=" << r.refused_value << ": " << e.what();
    }
    ++probed;
  }
  EXPECT_GT(probed, 200);
}

}  // namespace
}  // namespace msb
