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
  void key(const char* n, std::string& v, const Choices& c) override {
    seen[n] = c.text(), v = std::string("b");
  }  // (not = "b": GCC 12 -Wrestrict)
  void group(const char* n, const std::function<void(KeyVisitor&)>& body) override {
    seen[n] = "group";
    body(*this);
  }
  void moved(const char* n, const char*) override { seen[n] = "moved"; }
};

const MethodRegistration* probe() {
  static const std::vector<MethodRegistration> all = registeredMethods();
  for (const auto& r : all)
    if (r.info.type == "zz_probe") return &r;
  return nullptr;
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
