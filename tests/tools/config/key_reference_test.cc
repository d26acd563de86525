// The key reference (`msbench keys`, docs/keys.md): current, complete, and true — every key the
// reader accepts is listed with what it accepts, every number has a rule, and every rule refuses
// a value outside it through the real scenario reader, naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/explorer/method_registry.h"
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

// A method added in this test program, as a newcomer's folder would add one: docs/keys.md does
// not list it, and the reference test below still passes.
struct ExtraConfig {
  double reach_m = 3.0;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("reach_m", s.reach_m, Limits::positive());
  }
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
};
class ExtraExplorer final : public Explorer {
 public:
  ExtraExplorer(const ExtraConfig&, const ExplorerContext&) {}
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {}; }
};
const MethodRegistrar kExtra =
    registerMethod<ExtraExplorer, ExtraConfig>({"zz_extra", "a method docs/keys.md does not list", {}});

// The reference's sections by heading ("" for the text before the first), the footnote aside.
std::map<std::string, std::string> sections(std::string text) {
  const std::string footnote = "\n¹ read outside the key tables";
  if (const size_t f = text.rfind(footnote); f != std::string::npos) text.resize(f);
  std::map<std::string, std::string> out;
  std::string heading;
  size_t start = 0;
  while (true) {
    const size_t next = text.find("\n## ", start);
    out[heading] = text.substr(start, next == std::string::npos ? std::string::npos : next - start);
    if (next == std::string::npos) break;
    const size_t eol = text.find('\n', next + 1);
    heading = text.substr(next + 4, eol - next - 4);
    start = eol;
  }
  return out;
}

// docs/keys.md is current for every section it holds, and holds the shared keys, the paper's
// methods and `python`; a method added to the tree (zz_extra here) joins it when its author
// regenerates the file, and never fails the test before (docs/architecture.md).
TEST(KeyReference, TheDocsFileIsCurrent) {
  const std::string doc = readFile(fs::path(MSB_SOURCE_DIR) / "docs/keys.md");
  const std::string built = keyReferenceMarkdown();
  const char* regenerate = "docs/keys.md is out of date: regenerate it with `msbench keys > docs/keys.md`";
  EXPECT_EQ(doc.substr(doc.rfind("\n¹ ")), built.substr(built.rfind("\n¹ "))) << regenerate;
  const auto documented = sections(doc), current = sections(built);
  std::set<std::string> required = {"", "Scenario (flight, sensors, front end, mission, video)",
                                    "`method.type: python`"};
  for (const MethodRegistration& m : registeredMethods())
    if (m.info.listed < kListedAfterThePaper) required.insert("`method.type: " + m.info.type + "`");
  EXPECT_GE(required.size(), 6u);  // the three paper methods among them
  for (const auto& [heading, text] : current) {
    const auto it = documented.find(heading);
    if (it == documented.end()) {
      EXPECT_FALSE(required.count(heading)) << heading << " is missing; " << regenerate;
      continue;
    }
    EXPECT_EQ(it->second, text) << heading << ": " << regenerate;
  }
  for (const auto& [heading, text] : documented)
    EXPECT_TRUE(current.count(heading)) << heading << ": documented, but this msbench has no such section; "
                                        << regenerate;
  EXPECT_TRUE(current.count("`method.type: zz_extra`") && !documented.count("`method.type: zz_extra`"));
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
