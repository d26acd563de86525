// MonoSpheres' registration (the paper's method): method.type monospheres, its keys — the
// published code's switches (`reference_code`), the paper's four ablation switches, the mapper's
// and the planner's tables — the counters its progress line shows, its Table I rows, and its
// viewpoint chooser hook (setViewpointChooser, offered as "viewpoint_chooser").
#include "core/explorer/method_registry.h"
#include "core/methods/monospheres/planner/monospheres_explorer.h"

namespace msb {

namespace {

// reference_code first (a preset: `published` also applies the authors' settings, before the keys
// named beside it), then the switches, then map and planner.
void monoSpheresKeys(MonoSpheresConfig& c, KeyVisitor& v) {
  PresetKey reference_code;
  for (const auto& [name, member] : ReferenceCodeConfig::switches())
    reference_code.switches.emplace_back(name, &(c.reference_code.*member));
  reference_code.published_settings = [&c] { c.applyPublishedSettings(); };
  v.preset("reference_code", reference_code);
  v.group("switches", [&c](KeyVisitor& s) {
    s.key("ovde", c.map.ovde);
    s.key("dbof", c.map.dbof);
    s.key("fff", c.planner.goals.fff);
    s.key("vpb", c.planner.viewpoints.vpb);
  });
  ForwardKeys table(v);
  MonoSpheresConfig::fields(c, table);
}

}  // namespace

/// Registered before main() (the library is linked whole: docs/architecture.md).
const MethodRegistrar kMonoSpheresMethod = registerMethod<MonoSpheresExplorer, MonoSpheresConfig>(
    {"monospheres",
     "MonoSpheres: sphere map, frontier viewpoints, sphere-graph A* (the paper's method)",
     {"spheres", "reachable_spheres", "viewpoints", "goals_reached", "goals_chosen"},
     // The paper's Table I: the full method in the four worlds and its urban ablations.
     // Collisions (§V-C): two of the six urban runs; none in the cave; not given for the rest.
     {{"urban", "", 4919, 6081, 6, 2},
      {"cave", "", 7627, 8006, 3, 0},
      {"rooftops", "", 3760, 4606, 3},
      {"sparse", "", 5127, 5150, 3},
      {"urban", "fff", 2470, 3181, 3},
      {"urban", "dbof", 2308, 3081, 3},
      {"urban", "ovde", 747, 862, 3},
      {"urban", "vpb", 3697, 4175, 3}},
     /*listed=*/0,
     {{"viewpoint_chooser", hookOf(&MonoSpheresExplorer::setViewpointChooser)}}},
    monoSpheresKeys);

}  // namespace msb
