#include "tools/config/method_table.h"

#include <set>
#include <stdexcept>

#include "tools/config/field_keys.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "core/explorer/method_registry.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "tools/engine/methods.h"

namespace msb {

namespace {

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
  void key(const char* n, MapText& v) override { f_.key(n, v); }
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

// Reads the keys of `reg` under `method:` (except `type`) and finishes: its config, validated
// with its keys named under `method.`.
MethodChoice readRegistered(const MethodRegistration& reg, MapReader& m) {
  std::any config = reg.default_config();
  YamlKeyVisitor<MapReader> v(m);
  reg.keys(config, v);
  m.finish();
  ConfigChecker checker("method.");
  reg.validate(config, checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
  return registeredMethodChoice(reg, std::move(config));
}

}  // namespace

void readSphereMapKeys(MapReader& r, SphereMapConfig& c) { fieldKeys(r, c); }

MethodChoice readMethod(MapReader m) {
  std::string type = kDefaultMethodType;
  m.read("type", type);
  std::string names;
  std::set<std::string> types;
  for (const MethodRegistration& reg : methodRegistrations()) {
    if (type == reg.info.type) return readRegistered(reg, m);
    names += (names.empty() ? "" : ", ") + reg.info.type;
    types.insert(reg.info.type);
  }
  const std::string near = closestName(type, types);
  throw ConfigError(m.keyName("type"), "unknown method '" + type + "'" +
                                           (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                                           " (known: " + names + ")");
}

void writeMethod(MapWriter& w, const MethodChoice& method) {
  const MethodRegistration* reg = findRegistration(method.type);
  if (!reg) throw std::logic_error("writeMethod: method '" + method.type + "' is not registered");
  w.field("type", method.type);
  std::any c = method.config;
  YamlKeyVisitor<MapWriter> v(w);
  reg->keys(c, v);
}

std::string methodDefaultsYaml(const std::string& type, std::shared_ptr<MapWriter::KeyLog> log) {
  // An unknown type is refused as a scenario's `method.type` would be (naming the known ones).
  const MethodRegistration* reg = findRegistration(type);
  if (!reg) {
    YAML::Node tree(YAML::NodeType::Map);
    tree["method"]["type"] = type;
    struct MethodSection {
      void validate(ConfigChecker&) const {}
    };
    parseConfigNode<MethodSection>("--type", tree, [](MapReader& r, MethodSection&) { readMethod(r.sub("method")); });
    throw std::logic_error("methodDefaultsYaml: '" + type + "' read as a method but not registered");
  }
  // Every key with its default (a key a method requires, such as python's entry, shows empty).
  MapWriter w{YAML::Node(YAML::NodeType::Map), std::move(log)};
  MapWriter m = w.sub("method");
  m.field("type", type);
  std::any config = reg->default_config();
  YamlKeyVisitor<MapWriter> v(m);
  reg->keys(config, v);
  return yamlText(w.node());
}

}  // namespace msb
