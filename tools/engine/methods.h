// The exploration method of a mission as the loop sees it: a type name, a validated config and
// a factory. The methods register themselves from their folders (core/methods/<type>/,
// core/explorer/method_registry.h); a MethodChoice is made from a registration and a config
// (registeredMethodChoice), the one way a run's method is made. The default method of a scenario
// is a name looked up like any other (kDefaultMethodType, defaultMethod()).
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
  /// The hooks its explorer offers (MethodInfo::hooks), e.g. "goal_chooser".
  std::vector<NamedHook> hooks;
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

/// The hooks through which an outside goal chooser written in Python reaches a method (a
/// scenario's `goals:` section, docs/python.md): a list of goals ("goal_chooser", the grid's
/// GoalChooser) or a viewpoint to fly to ("viewpoint_chooser", MonoSpheres' ViewpointChooser).
inline constexpr const char* kGoalChooserHooks[] = {"goal_chooser", "viewpoint_chooser"};

/// True if `m`'s explorer takes an outside goal chooser (offers one of kGoalChooserHooks).
inline bool takesGoalChooser(const MethodChoice& m) {
  for (const char* h : kGoalChooserHooks)
    for (const NamedHook& offered : m.hooks)
      if (offered.name == h) return true;
  return false;
}

/// The hook through which the loop asks a method for its map as an OctoMap binary (`.bt`, as
/// liboctomap's writeBinary writes it): argument a std::string* the method fills. A run writes it
/// as map.bt (docs/interop.md).
inline constexpr char kOctomapBinaryHook[] = "octomap_binary";

/// The hook of `m` named `name`, or null.
inline const ExplorerHook* findHook(const MethodChoice& m, const std::string& name) {
  for (const NamedHook& h : m.hooks)
    if (h.name == name) return &h.hook;
  return nullptr;
}

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
