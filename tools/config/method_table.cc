#include "tools/config/method_table.h"

#include <set>
#include <stdexcept>

#include "tools/config/field_keys.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "core/explorer/method_registry.h"
#include "core/methods/monospheres/map/sphere_map.h"

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

// `python`: the door for methods written in Python, not a method of its own — its keys name
// the method (entry, path, params) and the binary hands its runs to the Python module. It stays
// here, the one entry not registered from a method's folder.
MethodEntry pythonEntry() {
  MethodEntry e;
  e.type = kPythonMethodType;
  e.summary = "a method written in Python (method.entry: \"package.module:factory\"; docs/python.md)";
  e.read = [](MapReader& m) {
    PythonMethodConfig c;
    pythonMethodKeys(m, c);
    m.finish();
    validateMethod(c);
    return methodChoice<PythonMethodStub>(kPythonMethodType, c);
  };
  e.write = [](const std::any& config, MapWriter& w) {
    PythonMethodConfig c = std::any_cast<const PythonMethodConfig&>(config);
    pythonMethodKeys(w, c);
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
  void preset(const char* n, const PresetKey& p) override {
    if constexpr (Keys::kReading) {
      readPreset(n, p);
    } else if (!p.switches.empty()) {
      auto w = k_.sub(n);
      for (const auto& [name, value] : p.switches) w.field(name, *value);
    }
  }

 private:
  // `reference_code: published | intended`, or a map of the switches (PresetKey).
  void readPreset(const char* n, const PresetKey& p) {
    if (!k_.has(n)) return;
    const YAML::Node node = k_.raw(n);
    const std::string key = k_.keyName(n);
    const bool named = node.IsScalar() && (node.Scalar() == "published" || node.Scalar() == "intended");
    if (p.switches.empty() && !named)
      throw ConfigError(key, std::string("expected published or intended") + p.why_no_map + ", got '" +
                                 (node.IsScalar() ? node.Scalar() : std::string("a map")) + "'");
    if (node.IsScalar() && !named)
      throw ConfigError(key, "expected published, intended or a map of switches, got '" + node.Scalar() + "'");
    bool all = named && node.Scalar() == "published";
    if (named) {
      for (const auto& sw : p.switches) *sw.second = all;
    } else {
      // In a map `published: true` turns every switch on first; the switches named beside it
      // then set their own value.
      MapReader r(node, key + ".");
      r.field("published", all);
      if (all)
        for (const auto& sw : p.switches) *sw.second = true;
      for (const auto& [name, value] : p.switches) r.field(name, *value);
      r.finish();
    }
    if (all && p.published_settings) p.published_settings();
  }

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
  e.paper_rows = reg.info.paper_rows;
  e.attach_goal_chooser = reg.attach_goal_chooser;
  e.read = [&reg](MapReader& m) {
    std::any config = reg.default_config();
    YamlKeyVisitor<MapReader> v(m);
    reg.keys(config, v);
    m.finish();
    ConfigChecker checker("method.");
    reg.validate(config, checker);
    if (!checker.issues().empty()) throw ConfigError(checker.issues());
    return registeredMethodChoice(reg, std::move(config));
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
  // Every method registered from its own folder (core/explorer/method_registry.h), the paper's
  // first in Table I's order, then `python`, then the others by type; the registrations outlive
  // the table, which points into them.
  static const std::vector<MethodRegistration>& registered = []() -> const std::vector<MethodRegistration>& {
    const std::vector<MethodRegistration>& r = methodRegistrations();
    for (const auto& reg : r)
      if (reg.info.type == kPythonMethodType)
        throw MethodRegistryError("method type '" + reg.info.type + "' is registered in " + reg.source_file +
                                  ", but it names methods written in Python (tools/config/method_table.cc); rename it");
    return r;
  }();
  static const std::vector<MethodEntry> all = [] {
    std::vector<MethodEntry> t;
    bool python_listed = false;
    for (const auto& reg : registered) {
      if (!python_listed && reg.info.listed >= kListedAfterThePaper) {
        t.push_back(pythonEntry());
        python_listed = true;
      }
      t.push_back(registeredEntry(reg));
    }
    if (!python_listed) t.push_back(pythonEntry());
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
  std::string type = kDefaultMethodType;
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
