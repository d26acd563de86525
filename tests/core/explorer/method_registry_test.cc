#include "core/explorer/method_registry.h"

#include <gtest/gtest.h>

#include <map>

namespace msb {
namespace {

// A method defined here, as a method folder would: a config with a key table and an explorer.
struct ProbeConfig {
  double radius_m = 2.0;
  int steps = 4;
  std::string mode = "a";
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("radius_m", s.radius_m, Limits::positive());
    v.key("steps", s.steps, Limits::range(1, 10));
    v.key("mode", s.mode, Choices{"a", "b"});
  }
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
};
class ProbeExplorer final : public Explorer {
 public:
  ProbeExplorer(const ProbeConfig& c, const ExplorerContext&) : radius_m_(c.radius_m) {}
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {{"radius_m", radius_m_}}; }

 private:
  double radius_m_;
};

const MethodRegistrar kProbe = registerMethod<ProbeExplorer, ProbeConfig>({"zz_probe", "a test method", {"radius_m"}});

// A KeyVisitor that records each key it is shown and sets the numbers it is given.
class Recorder final : public KeyVisitor {
 public:
  std::map<std::string, std::string> seen;
  void key(const char* n, double& v, const Limits& l) override { seen[n] = l.text(), v = 3.5; }
  void key(const char* n, int& v, const Limits& l) override { seen[n] = l.text(), v = 7; }
  void key(const char* n, uint64_t&, const Limits& l) override { seen[n] = l.text(); }
  void key(const char* n, Vec2&, const Limits& l) override { seen[n] = l.text(); }
  void key(const char* n, Vec3&, const Limits& l) override { seen[n] = l.text(); }
  void key(const char* n, std::array<double, 3>&, const Limits& l) override { seen[n] = l.text(); }
  void key(const char* n, std::array<double, 4>&, const Limits& l) override { seen[n] = l.text(); }
  void key(const char* n, bool&) override { seen[n] = "flag"; }
  void key(const char* n, std::string&) override { seen[n] = "text"; }
  void key(const char* n, MapText&) override { seen[n] = "map"; }
  void key(const char* n, std::string& v, const Choices& c) override {
    seen[n] = c.text(), v = std::string("b");
  }  // (not = "b": GCC 12 -Wrestrict)
  void group(const char* n, const std::function<void(KeyVisitor&)>& body) override {
    seen[n] = "group";
    body(*this);
  }
  void moved(const char* n, const char*) override { seen[n] = "moved"; }
  void preset(const char* n, const PresetKey& p) override {
    seen[n] = "preset of " + std::to_string(p.switches.size());
    for (const auto& sw : p.switches) *sw.second = true;  // as `published` does
    if (p.published_settings) p.published_settings();
  }
};

// A method whose registration carries everything the paper's methods need: its own keys (a
// preset, a section of switches, the table), Table I rows, a place in the list, the record's
// facts (switches()) and an outside goal chooser (setGoalChooser of its own chooser type).
struct TunedConfig {
  bool loud = false, fast = true;
  double gain = 1.0;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("gain", s.gain, Limits::positive());
  }
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
  std::map<std::string, bool> switches() const { return {{"fast", fast}}; }
};
using TunedChooser = std::function<int(int)>;
class TunedExplorer final : public Explorer {
 public:
  TunedExplorer(const TunedConfig&, const ExplorerContext&) {}
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {{"chosen", chooser_ ? chooser_(20) : -1}}; }
  void setGoalChooser(TunedChooser c) { chooser_ = std::move(c); }

 private:
  TunedChooser chooser_;
};
void tunedKeys(TunedConfig& c, KeyVisitor& v) {
  PresetKey p;
  p.switches = {{"loud", &c.loud}};
  p.published_settings = [&c] { c.gain = 9.0; };
  v.preset("reference_code", p);
  v.group("switches", [&c](KeyVisitor& s) { s.key("fast", c.fast); });
  ForwardKeys table(v);
  TunedConfig::fields(c, table);
}
const MethodRegistrar kTuned =
    registerMethod<TunedExplorer, TunedConfig>({"zz_tuned",
                                                "a tuned test method",
                                                {},
                                                {{"urban", "", 100, 200, 3, 1}},
                                                /*listed=*/5,
                                                {{"tuned_chooser", hookOf(&TunedExplorer::setGoalChooser)}}},
                                               tunedKeys);

const MethodRegistration* registered(const std::string& type) {
  static const std::vector<MethodRegistration> all = registeredMethods();
  for (const auto& r : all)
    if (r.info.type == type) return &r;
  return nullptr;
}
const MethodRegistration* probe() { return registered("zz_probe"); }

TEST(MethodRegistry, ARegistrationCarriesKeysRowsPlaceFactsAndChooser) {
  const MethodRegistration* r = registered("zz_tuned");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->info.listed, 5);
  ASSERT_EQ(r->info.paper_rows.size(), 1u);
  EXPECT_EQ(r->info.paper_rows[0].mean_area_m2, 100);
  EXPECT_EQ(r->info.paper_rows[0].collisions, 1);
  // The keys in order: the preset (which turned its switch on and applied its settings), the
  // switches, the table.
  std::any config = r->default_config();
  Recorder rec;
  r->keys(config, rec);
  EXPECT_EQ(rec.seen["reference_code"], "preset of 1");
  EXPECT_EQ(rec.seen["switches"], "group");
  EXPECT_EQ(rec.seen["fast"], "flag");
  const TunedConfig& c = std::any_cast<const TunedConfig&>(config);
  EXPECT_TRUE(c.loud);
  EXPECT_EQ(c.gain, 3.5);  // the table's key, visited after the preset's 9, wins
  EXPECT_EQ(r->facts(config).switches, (std::map<std::string, bool>{{"fast", true}}));
  EXPECT_EQ(r->facts(config).octree_resolution_m, 0.0);
  // The hook reaches the explorer with its own argument type; another type or another
  // method's explorer is refused.
  const ExplorerHook* hook = r->info.hook("tuned_chooser");
  ASSERT_NE(hook, nullptr);
  TunedExplorer x(c, ExplorerContext{});
  EXPECT_EQ(x.counters()["chosen"], -1);
  (*hook)(x, std::any(TunedChooser([](int v) { return v + 1; })));
  EXPECT_EQ(x.counters()["chosen"], 21);
  EXPECT_THROW((*hook)(x, std::any(3)), std::bad_any_cast);
  ProbeExplorer other(ProbeConfig{}, ExplorerContext{});
  EXPECT_THROW((*hook)(other, std::any(TunedChooser{})), std::logic_error);
  // A method that offers nothing has no hook.
  EXPECT_EQ(probe()->info.hook("tuned_chooser"), nullptr);
  EXPECT_TRUE(probe()->info.hooks.empty());
}

TEST(MethodRegistry, AStaticRegistrarAddsTheMethodBeforeMain) {
  EXPECT_EQ(kProbe.type, "zz_probe");
  const MethodRegistration* r = probe();
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->info.summary, "a test method");
  EXPECT_EQ(r->info.progress_counters, std::vector<std::string>{"radius_m"});
}

TEST(MethodRegistry, TheConfigIsVisitedValidatedAndBuiltThroughTheRegistration) {
  const MethodRegistration* r = probe();
  ASSERT_NE(r, nullptr);
  std::any config = r->default_config();
  Recorder rec;
  r->keys(config, rec);
  EXPECT_EQ(rec.seen["radius_m"], "> 0");
  EXPECT_EQ(rec.seen["steps"], "in [1, 10]");
  EXPECT_EQ(rec.seen["mode"], "a or b");
  EXPECT_EQ(std::any_cast<const ProbeConfig&>(config).radius_m, 3.5);  // the visitor wrote it
  ConfigChecker ok;
  r->validate(config, ok);
  EXPECT_TRUE(ok.issues().empty());
  std::any_cast<ProbeConfig&>(config).steps = 11;
  ConfigChecker bad("method.");
  r->validate(config, bad);
  ASSERT_EQ(bad.issues().size(), 1u);
  EXPECT_EQ(bad.issues()[0].key, "method.steps");
}

// (A type registered twice: test_core_method_registry_clash, a program of its own, since the
// clash makes every later use of that program's registry an error.)
TEST(MethodRegistry, TheListIsSortedAndNamesItsSourceFiles) {
  const auto all = registeredMethods();
  for (const auto& m : all) EXPECT_NE(m.source_file.find(".cc"), std::string::npos) << m.info.type;
  for (size_t i = 1; i < all.size(); ++i) EXPECT_LT(all[i - 1].info.type, all[i].info.type);
}

}  // namespace
}  // namespace msb
