// The exploration method of a mission as the loop sees it: a type name, a validated config and
// a factory. The methods register themselves from their folders (core/methods/<type>/,
// core/explorer/method_registry.h); a MethodChoice is made from a registration and a config
// (registeredMethodChoice), or from an explorer type and its config by methodChoice<Explorer>()
// (generic, for code that builds a method without the registry). The default method of a
// scenario is a name looked up like any other (kDefaultMethodType, defaultMethod()).
#pragma once

#include <any>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/explorer/explorer.h"
#include "core/explorer/method_registry.h"

namespace msb {

/// The method of a scenario: its type, its validated config and a factory.
struct MethodChoice {
  std::string type;                      ///< as in `method.type`
  std::any config;                       ///< the method's config struct (e.g. MonoSpheresConfig)
  std::map<std::string, bool> switches;  ///< the method's on/off switches (ablations), for reports
  /// The published code's defects the method runs with (MonoSpheres' method.reference_code;
  /// empty for methods without them), for the record and report labels.
  std::map<std::string, bool> reference_code;
  /// > 0: the method's free space is OctoMap cells of this leaf size, which the authors'
  /// evaluation rule (BUG-11) also scores (coverage.area_published_rule_m2); 0: not applicable.
  double octree_resolution_m = 0.0;
  /// True if the explorer takes an outside goal chooser (a goal or viewpoint chooser hook).
  bool takes_goal_chooser = false;
  /// Creates the explorer for a mission.
  std::function<std::unique_ptr<Explorer>(const FisheyeCamera&, const ExplorerContext&)> make;
  /// Why the method that flew cannot be rebuilt from the scenario ("" = it can): an in-process
  /// Python factory or goal chooser that has no importable name. metrics.json then says
  /// `replayable: false` and config.yaml opens with the reason.
  std::string not_replayable;
  /// The in-process goal chooser that chose the goals ("module:qualname"; "" = the method's own).
  std::string goal_chooser;
  /// Where a method msbench did not compile ran: "own process, Landlock ABI 7", "in-process
  /// (unconfined)", ... ("" = compiled into msbench: reviewed source, trusted).
  std::string confinement;
};

/// The MethodChoice of `ExplorerT` with `config` (validated here; throws ConfigError). The
/// explorer is constructed from (config, camera, context) or (config, context); the switches are
/// the config's `switches()` if it has one (the paper's ablation switches), else none.
template <class ExplorerT, class Config>
MethodChoice methodChoice(std::string type, const Config& config) {
  const Config c = checkValid(config);
  MethodChoice m;
  m.type = std::move(type);
  m.config = c;
  MethodFacts facts = methodFactsOf(c);
  m.switches = std::move(facts.switches);
  m.reference_code = std::move(facts.reference_code);
  m.octree_resolution_m = facts.octree_resolution_m;
  m.takes_goal_chooser = requires(ExplorerT & x) { x.setGoalChooser({}); }
  || requires(ExplorerT & x) { x.setViewpointChooser({}); };
  m.make = [c](const FisheyeCamera& camera, const ExplorerContext& context) -> std::unique_ptr<Explorer> {
    if constexpr (std::is_constructible_v<ExplorerT, const Config&, const FisheyeCamera&, const ExplorerContext&>)
      return std::make_unique<ExplorerT>(c, camera, context);
    else
      return std::make_unique<ExplorerT>(c, context);
  };
  return m;
}

/// The method as reports name it: its type, each ablation switch that is off ("monospheres
/// -ovde"), and the published code's defects that are on ("+published" when all are).
inline std::string methodLabel(const MethodChoice& m) {
  std::string label = m.type, on;
  for (const auto& [name, value] : m.switches)
    if (!value) label += " -" + name;
  bool all = true;
  for (const auto& [name, value] : m.reference_code) {
    all = all && value;
    if (value) on += " +" + name;
  }
  return label + (all && !on.empty() ? " +published" : on);
}

/// The `method.type` of a method written in Python (docs/python.md).
inline constexpr char kPythonMethodType[] = "python";

/// A method written in Python: where its factory is and the keys it is given. The C++ binary
/// embeds no Python, so `msbench run` hands such a scenario to the Python module, which builds
/// the method from these and runs the same loop (docs/python.md).
struct PythonMethodConfig {
  std::string entry;               ///< "package.module:factory"
  std::string path;                ///< a directory put first on sys.path (relative: to the scenario file)
  std::string params_yaml = "{}";  ///< the method's own keys (a YAML map), the factory's keyword arguments
  double call_budget_s = 60.0;     ///< wall-clock seconds each call of its process may take (a method only)
  double memory_limit_mib = 4096;  ///< its process's address space (RLIMIT_AS; a method only)

  /// A method's keys, each once (`params` is read in tools/config; a goal chooser reads entry,
  /// path and params only).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("entry", s.entry);
    v.key("path", s.path);
    v.key("call_budget_s", s.call_budget_s, Limits::range(0.1, 86400.0));
    v.key("memory_limit_mib", s.memory_limit_mib, Limits::range(256.0, 1048576.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const {
    checkFields(*this, c);
    const auto colon = entry.find(':');
    c.require(colon != std::string::npos && colon > 0 && colon + 1 < entry.size() &&
                  entry.find(':', colon + 1) == std::string::npos,
              "entry", "must be \"package.module:factory\", got '" + entry + "'");
  }
};

/// The `method.type` of a scenario that names none: the paper's method.
inline constexpr char kDefaultMethodType[] = "monospheres";

/// Every method registered from its folder (registeredMethods()), the paper's first in Table I's
/// order, then the others by type; read once, and kept for the program's life (a MethodChoice's
/// factory points into it). Throws MethodRegistryError as registeredMethods() does.
const std::vector<MethodRegistration>& methodRegistrations();

/// The registration of `type`, or null.
const MethodRegistration* findRegistration(const std::string& type);

/// The MethodChoice of registration `reg` (one of methodRegistrations()) with `config`, a config
/// of its type that the caller has validated.
MethodChoice registeredMethodChoice(const MethodRegistration& reg, std::any config);

/// The default method (kDefaultMethodType) with its defaults. Throws std::logic_error when the
/// program was linked without it (a build defect, not an input).
MethodChoice defaultMethod();

}  // namespace msb
