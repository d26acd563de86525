// The test seam of MonoSpheresExplorer: its map, for hand-built scenes in tests (with
// SphereMapTestSeam). The explorer builds its map from frames alone; tests reach it here, by name.
#pragma once

#include "core/methods/monospheres/planner/monospheres_explorer.h"

namespace msb {

/// Direct access to an explorer's state, for tests only.
struct MonoSpheresTestSeam {
  /// The explorer's sphere map, to edit by hand.
  static SphereMap& map(MonoSpheresExplorer& explorer) { return explorer.map_; }
  /// The configuration the explorer's parts were built with (the switches applied).
  static const MonoSpheresConfig& config(const MonoSpheresExplorer& explorer) { return explorer.config_; }
};

}  // namespace msb
