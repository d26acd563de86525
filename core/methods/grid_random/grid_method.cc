// The grid baseline's registration (the paper's Grid-Based rows): method.type grid_random, its
// keys — `reference_code: published` (the authors' grid session's settings) and its table — the
// counters its progress line shows, its Table I rows and its hooks: the goal chooser (setGoalChooser, "goal_chooser")
// and its OctoMap as .bt
// ("octomap_binary").
#include "core/explorer/method_registry.h"
#include "core/methods/grid_random/grid_explorer.h"

namespace msb {

namespace {

// `reference_code: published` (applied before the keys named beside it; not written back: the
// keys it set are) or `intended`, then the grid's table.
void gridKeys(GridExplorerConfig& c, KeyVisitor& v) {
  PresetKey reference_code;
  reference_code.published_settings = [&c] { c.applyPublishedSettings(); };
  reference_code.why_no_map = " (the grid has no switches)";
  v.preset("reference_code", reference_code);
  ForwardKeys table(v);
  GridExplorerConfig::fields(c, table);
}

}  // namespace

/// Registered before main() (the library is linked whole: docs/architecture.md).
const MethodRegistrar kGridMethod = registerMethod<GridExplorer, GridExplorerConfig>(
    {"grid_random",
     "grid baseline: OctoMap, random goals, grid A* (the paper's Grid-Based rows)",
     {"leaves", "goals_reached", "goals_chosen"},
     // Collisions (§V-C): one of the six urban runs (a metal rod); none in the cave.
     {{"urban", "", 1911, 2306, 6, 1},
      {"cave", "", 3171, 3375, 3, 0},
      {"rooftops", "", 1360, 1556, 3},
      {"sparse", "", 2108, 2168, 3}},
     /*listed=*/1,
     {{"goal_chooser", hookOf(&GridExplorer::setGoalChooser)},
      {"octomap_binary", hookOf(&GridExplorer::octomapBinary)}}},
    gridKeys);

}  // namespace msb
