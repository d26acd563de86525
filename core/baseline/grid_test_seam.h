// The test seam of the grid-map explorers (GridExplorer, StarDiscoveryExplorer): their OctoMap,
// for hand-built scenes in tests. The explorers build their maps from frames alone; tests reach
// them here, by name.
#pragma once

#include "core/baseline/grid_explorer.h"
#include "core/baseline/star_discovery_explorer.h"

namespace msb {

/// Direct access to a grid-map explorer's map, for tests only.
struct GridExplorerTestSeam {
  /// The explorer's map, to edit by hand.
  static GridMap& map(GridExplorer& explorer) { return explorer.map_; }
  static GridMap& map(StarDiscoveryExplorer& explorer) { return explorer.map_; }
};

}  // namespace msb
