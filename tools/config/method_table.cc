#include "tools/config/method_table.h"

#include <set>
#include <stdexcept>

#include "tools/config/field_keys.h"

#include <yaml-cpp/yaml.h>

#include "core/baseline/grid_explorer.h"
#include "core/baseline/star_discovery_explorer.h"
#include "core/explorer/method_registry.h"
#include "core/planning/monospheres_explorer.h"

namespace msb {

namespace {

// Validates a method's config with its keys named under `method.` (before methodChoice()
// validates it again without the prefix).
template <class Config>
void validateMethod(const Config& c) {
  ConfigChecker checker("method.");
  c.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
}

// The published code's defects (docs/deviations.md, "The published code as switches"):
//   reference_code: published            every modelled defect on (`intended`: none)
//   reference_code: {path_resend_8s: true, ...}        the switches named
//   reference_code: {published: true, heading_check_signed: false}
// In a map `published: true` turns every switch on first; switches named beside it then set
// their own value. Written back as the full map of switches.
// Returns true when the whole published code is named (`published`, or `published: true` in a
// map): the authors' settings then apply too (MonoSpheresConfig::applyPublishedSettings).
template <class Keys>
bool referenceCodeKeys(Keys& m, ReferenceCodeConfig& c) {
  if constexpr (Keys::kReading) {
    if (!m.has("reference_code")) return false;
    const YAML::Node n = m.raw("reference_code");
    const std::string key = m.keyName("reference_code");
    if (n.IsScalar()) {
      if (n.Scalar() != "published" && n.Scalar() != "intended")
        throw ConfigError(key, "expected published, intended or a map of switches, got '" + n.Scalar() + "'");
      c = n.Scalar() == "published" ? ReferenceCodeConfig::published() : ReferenceCodeConfig{};
      return n.Scalar() == "published";
    }
    MapReader r(n, key + ".");
    bool all = false;
    r.field("published", all);
    if (all) c = ReferenceCodeConfig::published();
    for (const auto& [name, member] : ReferenceCodeConfig::switches()) r.field(name, c.*member);
    r.finish();
    return all;
  } else {
    auto w = m.sub("reference_code");
    for (const auto& [name, member] : ReferenceCodeConfig::switches()) w.field(name, c.*member);
    return false;
  }
}

// MonoSpheres: switches, the published code's switches (and with the whole published code, the
// authors' settings, before the keys named beside it), mapper and planner keys.
template <class Keys>
void monoSpheresKeys(Keys& m, MonoSpheresConfig& c) {
  if (referenceCodeKeys(m, c.reference_code)) c.applyPublishedSettings();
  if (m.has("switches")) {
    auto w = m.sub("switches");
    w.field("ovde", c.map.ovde);
    w.field("dbof", c.map.dbof);
    w.field("fff", c.planner.fff);
    w.field("vpb", c.planner.viewpoints.vpb);
    w.finish();
  }
  fieldKeys(m, c);  // map, planner
}

// The grid: `reference_code: published` (the authors' grid session's settings, applied before the
// keys named beside it; not written back: the keys it set are) or `intended`, then its table.
template <class Keys>
void gridKeys(Keys& m, GridExplorerConfig& c) {
  if constexpr (Keys::kReading) {
    if (m.has("reference_code")) {
      const YAML::Node n = m.raw("reference_code");
      if (!n.IsScalar() || (n.Scalar() != "published" && n.Scalar() != "intended"))
        throw ConfigError(m.keyName("reference_code"),
                          "expected published or intended (the grid has no switches), got '" +
                              (n.IsScalar() ? n.Scalar() : std::string("a map")) + "'");
      if (n.Scalar() == "published") c.applyPublishedSettings();
    }
  }
  fieldKeys(m, c);
}

// A Python method's keys: entry and path, and `params`, a map passed through to its factory
// (which validates it) — read as YAML text, written back as the same map.
template <class Keys>
void pythonMethodKeys(Keys& m, PythonMethodConfig& c) {
  fieldKeys(m, c);
  if constexpr (Keys::kReading) {
    if (m.has("params")) c.params_yaml = m.flowMap("params", "the method's own keys");
  } else {
    m.node()["params"] = YAML::Load(c.params_yaml);
  }
}

// The explorer slot of a Python method: the C++ binary cannot build one (the Python module does).
class PythonMethodStub final : public Explorer {
 public:
  PythonMethodStub(const PythonMethodConfig&, const ExplorerContext&) {
    throw ConfigError("method.type",
                      "'python' methods run through the Python module: msbench run hands them to "
                      "/usr/bin/python3 -m msbench (docs/python.md)");
  }
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {}; }
};

// One method-table entry from the method's explorer and config types and its keys function
// (`keys(k, config)` for any key visitor k: MapReader reads, MapWriter writes).
template <class ExplorerT, class Config, class KeysFn>
MethodEntry methodEntry(const char* type, const char* summary, KeysFn keys, std::vector<std::string> progress,
                        std::vector<PaperRow> paper_rows = {}) {
  MethodEntry e;
  e.type = type;
  e.summary = summary;
  e.paper_rows = std::move(paper_rows);
  e.progress_counters = std::move(progress);
  e.read = [type, keys](MapReader& m) {
    Config c;
    keys(m, c);
    m.finish();
    validateMethod(c);
    return methodChoice<ExplorerT>(type, c);
  };
  e.write = [keys](const std::any& config, MapWriter& w) {
    Config c = std::any_cast<const Config&>(config);
    keys(w, c);
  };
  // An outside goal chooser for the explorers that take one (a compile-time check on the
  // explorer type): the grid its goals, MonoSpheres its viewpoints. `x` is an explorer this
  // entry made, so the cast is exact.
  if constexpr (requires(ExplorerT & x, GoalChooser g) { x.setGoalChooser(g); })
    e.attach_goal_chooser = [](Explorer& x, const GoalChoosers& c) {
      static_cast<ExplorerT&>(x).setGoalChooser(c.goals);
    };
  if constexpr (requires(ExplorerT & x, ViewpointChooser v) { x.setViewpointChooser(v); })
    e.attach_goal_chooser = [](Explorer& x, const GoalChoosers& c) {
      static_cast<ExplorerT&>(x).setViewpointChooser(c.viewpoints);
    };
  return e;
}

// A registered method's key table over a MapReader or MapWriter (through the virtual visitor).
template <class Keys>
class YamlKeyVisitor final : public KeyVisitor {
 public:
  explicit YamlKeyVisitor(Keys& k) : k_(k), f_(k) {}
  void key(const char* n, double& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, int& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, uint64_t& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, Vec2& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, Vec3& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, std::array<double, 3>& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, std::array<double, 4>& v, const Limits& l) override { f_.key(n, v, l); }
  void key(const char* n, bool& v) override { f_.key(n, v); }
  void key(const char* n, std::string& v) override { f_.key(n, v); }
  void key(const char* n, std::string& v, const Choices& c) override { f_.key(n, v, c); }
  void group(const char* n, const std::function<void(KeyVisitor&)>& body) override {
    if (!k_.has(n)) return;
    auto sub = k_.sub(n);
    YamlKeyVisitor<decltype(sub)> inner(sub);
    body(inner);
    sub.finish();
  }
  void moved(const char* n, const char* where) override { f_.moved(n, where); }

 private:
  Keys& k_;
  FieldKeys<Keys> f_;
};

// The method-table entry of a method that registered itself from its folder: its keys through
// its config's table, validated with their `method.` names, its explorer from the registration.
MethodEntry registeredEntry(const MethodRegistration& reg) {
  MethodEntry e;
  e.type = reg.info.type.c_str();
  e.summary = reg.info.summary.c_str();
  e.progress_counters = reg.info.progress_counters;
  e.read = [&reg](MapReader& m) {
    std::any config = reg.default_config();
    YamlKeyVisitor<MapReader> v(m);
    reg.keys(config, v);
    m.finish();
    ConfigChecker checker("method.");
    reg.validate(config, checker);
    if (!checker.issues().empty()) throw ConfigError(checker.issues());
    MethodChoice choice;
    choice.type = reg.info.type;
    choice.config = config;
    choice.make = [&reg, config](const FisheyeCamera& camera, const ExplorerContext& context) {
      return reg.make(config, camera, context);
    };
    return choice;
  };
  e.write = [&reg](const std::any& config, MapWriter& w) {
    std::any c = config;
    YamlKeyVisitor<MapWriter> v(w);
    reg.keys(c, v);
  };
  return e;
}

}  // namespace

void readSphereMapKeys(MapReader& r, SphereMapConfig& c) { fieldKeys(r, c); }

const std::vector<MethodEntry>& methodTable() {
  // One entry per method: explorer and config types, `method.type`, summary, keys, Table I rows.
  static const std::vector<MethodEntry> table = {
      // MonoSpheres paper, Table I: the full method in the four worlds and its urban ablations.
      methodEntry<MonoSpheresExplorer, MonoSpheresConfig>(
          kMonoSpheresType, "MonoSpheres: sphere map, frontier viewpoints, sphere-graph A* (the paper's method)",
          [](auto& k, MonoSpheresConfig& c) { monoSpheresKeys(k, c); },
          {"spheres", "reachable_spheres", "viewpoints", "goals_reached", "goals_chosen"},
          // Collisions (§V-C): two of the six urban runs; none in the cave; not given for the rest.
          {{"urban", "", 4919, 6081, 6, 2},
           {"cave", "", 7627, 8006, 3, 0},
           {"rooftops", "", 3760, 4606, 3},
           {"sparse", "", 5127, 5150, 3},
           {"urban", "fff", 2470, 3181, 3},
           {"urban", "dbof", 2308, 3081, 3},
           {"urban", "ovde", 747, 862, 3},
           {"urban", "vpb", 3697, 4175, 3}}),
      methodEntry<GridExplorer, GridExplorerConfig>(
          "grid_random", "grid baseline: OctoMap, random goals, grid A* (the paper's Grid-Based rows)",
          [](auto& k, GridExplorerConfig& c) { gridKeys(k, c); }, {"leaves", "goals_reached", "goals_chosen"},
          // Collisions (§V-C): one of the six urban runs (a metal rod); none in the cave.
          {{"urban", "", 1911, 2306, 6, 1},
           {"cave", "", 3171, 3375, 3, 0},
           {"rooftops", "", 1360, 1556, 3},
           {"sparse", "", 2108, 2168, 3}}),
      methodEntry<StarDiscoveryExplorer, StarDiscoveryConfig>(
          "star_discovery", "star discovery (von Stumberg et al.): look-around, star flights, interesting cells",
          [](auto& k, StarDiscoveryConfig& c) { fieldKeys(k, c); },
          {"leaves", "stars", "interesting_cells", "goals_reached"}),
      methodEntry<PythonMethodStub, PythonMethodConfig>(
          kPythonMethodType, "a method written in Python (method.entry: \"package.module:factory\"; docs/python.md)",
          [](auto& k, PythonMethodConfig& c) { pythonMethodKeys(k, c); }, {}),
  };
  // Then every method registered from its own folder (core/explorer/method_registry.h), by type;
  // the registrations outlive the table, which points into them.
  static const std::vector<MethodRegistration> registered = registeredMethods();
  static const std::vector<MethodEntry> all = [] {
    std::vector<MethodEntry> t = table;
    for (const auto& reg : registered) {
      for (const auto& built_in : table)
        if (reg.info.type == built_in.type)
          throw MethodRegistryError("method type '" + reg.info.type + "' is registered twice: built into " +
                                    "tools/config/method_table.cc and in " + reg.source_file + "; rename the latter");
      t.push_back(registeredEntry(reg));
    }
    return t;
  }();
  return all;
}

const MethodEntry* findMethod(const std::string& type) {
  for (const auto& e : methodTable())
    if (type == e.type) return &e;
  return nullptr;
}

MethodChoice readMethod(MapReader m) {
  std::string type = kMonoSpheresType;
  m.read("type", type);
  std::string names;
  for (const auto& e : methodTable()) {
    if (type == e.type) return e.read(m);
    names += (names.empty() ? "" : ", ") + std::string(e.type);
  }
  std::set<std::string> types;
  for (const auto& e : methodTable()) types.insert(e.type);
  const std::string near = closestName(type, types);
  throw ConfigError(m.keyName("type"), "unknown method '" + type + "'" +
                                           (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                                           " (known: " + names + ")");
}

void writeMethod(MapWriter& w, const MethodChoice& method) {
  const MethodEntry* e = findMethod(method.type);
  if (!e) throw std::logic_error("writeMethod: method '" + method.type + "' is not in the method table");
  w.field("type", method.type);
  e->write(method.config, w);
}

std::string methodDefaultsYaml(const std::string& type, std::shared_ptr<MapWriter::KeyLog> log) {
  // A `method:` section that names only the type: every other key takes its default.
  struct MethodSection {
    MethodChoice choice;
    void validate(ConfigChecker&) const {}
  };
  YAML::Node tree(YAML::NodeType::Map);
  tree["method"]["type"] = type;
  if (type == kPythonMethodType) tree["method"]["entry"] = "package.module:factory";  // required: a placeholder
  const MethodSection section = parseConfigNode<MethodSection>("--type", tree, [](MapReader& r, MethodSection& s) {
    s.choice = readMethod(r.sub("method"));
    r.finish();
  });
  MapWriter w{YAML::Node(YAML::NodeType::Map), std::move(log)};
  MapWriter m = w.sub("method");
  writeMethod(m, section.choice);
  return yamlText(w.node());
}

}  // namespace msb
