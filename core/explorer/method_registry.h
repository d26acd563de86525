// Methods that register themselves from their own folder (docs/architecture.md, "How to add an
// exploration method"): one line in the method's own source,
//
//   const MethodRegistrar kRegistered = registerMethod<HoverTurnExplorer, HoverTurnConfig>(
//       {"hover_turn", "example method: take off, turn once, descend", {"turn_steps", "points_seen"}});
//
// adds it to the methods msbench knows — `method.type: hover_turn` in a scenario, its keys read,
// written and validated through its config's key table (core/common/config_fields.h), its
// explorer built by the loop, `msbench methods` listing it — with no edit outside the folder.
// A registration is the one descriptor of a method: the run's choice is made from it and a
// config (registeredMethodChoice, tools/engine/methods.h), and what a method offers beyond the
// Explorer interface it names as hooks (MethodInfo::hooks), which this registry never names.
// This header depends on core/common alone (the camera is only declared): a method's folder
// stays free of the YAML layer, which visits the table through the virtual KeyVisitor.
#pragma once

#include <any>
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <source_location>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/common/config_fields.h"
#include "core/explorer/explorer.h"

namespace msb {

class FisheyeCamera;
struct PresetKey;

/// A key table visited through virtual calls (the YAML layer implements it): the same calls as
/// a table's template visitor, for the types a table may hold.
class KeyVisitor {
 public:
  virtual ~KeyVisitor() = default;
  virtual void key(const char* name, double& v, const Limits& l) = 0;
  virtual void key(const char* name, int& v, const Limits& l) = 0;
  virtual void key(const char* name, uint64_t& v, const Limits& l) = 0;
  virtual void key(const char* name, Vec2& v, const Limits& l) = 0;
  virtual void key(const char* name, Vec3& v, const Limits& l) = 0;
  virtual void key(const char* name, std::array<double, 3>& v, const Limits& l) = 0;
  virtual void key(const char* name, std::array<double, 4>& v, const Limits& l) = 0;
  virtual void key(const char* name, bool& v) = 0;
  virtual void key(const char* name, std::string& v) = 0;
  virtual void key(const char* name, std::string& v, const Choices& c) = 0;
  virtual void key(const char* name, MapText& v) = 0;
  /// A nested group: `body` visits its keys with the visitor of the group.
  virtual void group(const char* name, const std::function<void(KeyVisitor&)>& body) = 0;
  virtual void moved(const char* name, const char* where) = 0;
  /// A preset key (PresetKey), visited before the keys it presets.
  virtual void preset(const char* name, const PresetKey& p) = 0;
};

/// A key that names a preset of the published code (`reference_code: published | intended`) or,
/// when the method has switches for it, a map of those switches in which `published: true` turns
/// every switch on first and the switches named beside it then set their own value. `published`
/// also applies `published_settings` (the authors' values), before the keys visited after it, so
/// a key a scenario names beside the preset wins. Written back as the map of switches (nothing
/// when there are none: the keys it set are written instead).
struct PresetKey {
  std::vector<std::pair<const char*, bool*>> switches;  ///< the map form's switches (empty: a name only)
  std::function<void()> published_settings;             ///< what `published` applies beyond the switches
  const char* why_no_map = "";                          ///< said when a map is given and there are no switches
};

/// The template visitor a table's fields() is called with, forwarding to a KeyVisitor.
class ForwardKeys {
 public:
  explicit ForwardKeys(KeyVisitor& v) : v_(v) {}
  template <class T, class... Rule>
  void key(const char* name, T& value, const Rule&... rule) {
    v_.key(name, value, rule...);
  }
  template <class Sub>
  void group(const char* name, Sub& sub) {
    v_.group(name, [&sub](KeyVisitor& inner) {
      ForwardKeys f(inner);
      Sub::fields(sub, f);
    });
  }
  void moved(const char* name, const char* where) { v_.moved(name, where); }

 private:
  KeyVisitor& v_;
};

/// A row of the paper's Table I that a method answers to (mean and max A over its runs, m²; the
/// runs; the runs that ended in a collision where §V-C says how many). The one source of the
/// paper's figures: the report's rows and its findings read them from the method's registration.
struct PaperRow {
  const char* world;         ///< urban, cave, rooftops, sparse
  const char* switched_off;  ///< "" for the full method, else the one switch an ablation turns off
  double mean_area_m2, max_area_m2;
  int runs = 0;         ///< Table I's "Runs"
  int collisions = -1;  ///< runs ended by a collision (-1: the paper does not say)
};

/// MethodInfo::listed of every method that is not one of the paper's.
inline constexpr int kListedAfterThePaper = 100;

/// An optional capability of a method's explorer beyond the Explorer interface, offered under a
/// name its users know (the Python goal-only helper looks for "goal_chooser" and
/// "viewpoint_chooser", docs/python.md): called on an explorer the method made, with an argument
/// of the type the hook takes, in a std::any (std::bad_any_cast for any other type).
using ExplorerHook = std::function<void(Explorer& explorer, const std::any& argument)>;

/// The ExplorerHook that calls `fn`, a const one-argument member function of ExplorerT (a hook
/// that reports, such as one that writes the method's map into a string the caller gives).
template <class ExplorerT, class Arg>
ExplorerHook hookOf(void (ExplorerT::*fn)(Arg) const) {
  return [fn](Explorer& x, const std::any& a) {
    auto* own = dynamic_cast<ExplorerT*>(&x);
    if (!own) throw std::logic_error("a method's hook was called on another method's explorer");
    (own->*fn)(std::any_cast<const std::decay_t<Arg>&>(a));
  };
}

/// A hook and the name it is offered under (MethodInfo::hooks).
struct NamedHook {
  std::string name;   ///< letters, digits and '_'
  ExplorerHook hook;  ///< what it does
};

/// The ExplorerHook that calls `setter`, a one-argument member function of ExplorerT, with the
/// argument. Throws std::logic_error on an explorer that is not an ExplorerT.
template <class ExplorerT, class Arg>
ExplorerHook hookOf(void (ExplorerT::*setter)(Arg)) {
  return [setter](Explorer& x, const std::any& a) {
    auto* own = dynamic_cast<ExplorerT*>(&x);
    if (!own) throw std::logic_error("a method's hook was called on another method's explorer");
    (own->*setter)(std::any_cast<const std::decay_t<Arg>&>(a));
  };
}

/// What a method says about itself when it registers.
struct MethodInfo {
  std::string type;                            ///< `method.type` (letters, digits and '_', not empty)
  std::string summary;                         ///< one line, for `msbench methods` and errors
  std::vector<std::string> progress_counters;  ///< the counters the progress line shows, in order
  std::vector<PaperRow> paper_rows = {};       ///< the Table I rows it answers to (none: not in the paper)
  /// Where `msbench methods` lists it: the paper's methods first (0, 1, 2 in Table I's order),
  /// every other method after them (the default), by type.
  int listed = kListedAfterThePaper;
  std::vector<NamedHook> hooks = {};  ///< the capabilities it offers (names unique), none by default

  /// The hook offered as `name`, or null.
  const ExplorerHook* hook(const std::string& name) const {
    for (const auto& h : hooks)
      if (h.name == name) return &h.hook;
    return nullptr;
  }
};

/// What the run's record says of a method's config (from the config's own functions, if it has
/// them): the paper's ablation switches (`switches()`), the published code's defects
/// (`referenceCode()`), the OctoMap leaf of its free space (`octreeResolutionM()`, 0: none).
struct MethodFacts {
  std::map<std::string, bool> switches, reference_code;
  double octree_resolution_m = 0.0;
};

/// The facts of `config` (MethodFacts) from the functions its type has.
template <class Config>
MethodFacts methodFactsOf(const Config& c) {
  MethodFacts f;
  if constexpr (requires { c.switches(); }) f.switches = c.switches();
  if constexpr (requires { c.referenceCode(); }) f.reference_code = c.referenceCode();
  if constexpr (requires { c.octreeResolutionM(); }) f.octree_resolution_m = c.octreeResolutionM();
  return f;
}

/// A registered method: its info and its config and explorer, type-erased.
struct MethodRegistration {
  MethodInfo info;
  std::string source_file;                   ///< the source file that registered it (for errors naming both of a clash)
  std::function<std::any()> default_config;  ///< the config with its defaults
  std::function<void(std::any& config, KeyVisitor& keys)> keys;            ///< visits the config's key table
  std::function<void(const std::any& config, ConfigChecker& c)> validate;  ///< the config's validate()
  std::function<MethodFacts(const std::any& config)> facts;                ///< what the record says of it
  /// Builds the explorer from a (validated) config.
  std::function<std::unique_ptr<Explorer>(const std::any& config, const FisheyeCamera& camera,
                                          const ExplorerContext& context)>
      make;
};

/// A registration that cannot be used: two methods under one type name, an empty or malformed
/// name. The message names the source files. Bad input of the build, not a crash: commands that
/// need the methods exit 2 with it; the others (`--help`) run.
class MethodRegistryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every method registered so far, sorted by type (static registrars run before main()). Throws
/// MethodRegistryError naming the files if a registration clashed or was malformed.
std::vector<MethodRegistration> registeredMethods();

/// Adds a registration; registerMethod() calls it. Never throws (it runs before main()): a clash
/// is kept and reported by registeredMethods().
void addMethodRegistration(MethodRegistration r) noexcept;

/// The proof that a method registered (keep it as a namespace-scope constant of the method).
struct MethodRegistrar {
  std::string type;
};

/// A method's keys beyond its config's table (a preset, a section of switches): visits them and
/// the table, in the order they are read and written.
template <class Config>
using MethodKeysFn = void (*)(Config& config, KeyVisitor& keys);

/// Registers `ExplorerT` with its `Config` (which has a key table and validate()); the explorer
/// is constructed from (config, camera, context) or (config, context). `keys` (default: the
/// config's table alone) visits the method's keys.
template <class ExplorerT, class Config>
MethodRegistrar registerMethod(MethodInfo info, MethodKeysFn<Config> keys = nullptr,
                               std::source_location where = std::source_location::current()) {
  MethodRegistration r;
  r.info = info;
  r.source_file = where.file_name();
  r.default_config = [] { return std::any(Config{}); };
  r.keys = [keys](std::any& config, KeyVisitor& v) {
    Config& c = std::any_cast<Config&>(config);
    if (keys) return keys(c, v);
    ForwardKeys f(v);
    Config::fields(c, f);
  };
  r.validate = [](const std::any& config, ConfigChecker& c) { std::any_cast<const Config&>(config).validate(c); };
  r.facts = [](const std::any& config) { return methodFactsOf(std::any_cast<const Config&>(config)); };
  r.make = [](const std::any& config, const FisheyeCamera& camera,
              const ExplorerContext& context) -> std::unique_ptr<Explorer> {
    const Config& c = std::any_cast<const Config&>(config);
    if constexpr (std::is_constructible_v<ExplorerT, const Config&, const FisheyeCamera&, const ExplorerContext&>)
      return std::make_unique<ExplorerT>(c, camera, context);
    else
      return std::make_unique<ExplorerT>(c, context);
  };
  addMethodRegistration(std::move(r));
  return {info.type};
}

}  // namespace msb
