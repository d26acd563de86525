// The test seam of the grid map and the grid-map explorers (GridExplorer, StarDiscoveryExplorer):
// their OctoMap, for hand-built scenes in tests. The maps are built from frames alone; tests
// reach them here, by name.
#pragma once

#include "core/baseline/grid_explorer.h"
#include "core/baseline/star_discovery_explorer.h"

namespace msb {

/// Direct access to a grid map's octree, for hand-built maps in tests only.
struct GridMapTestSeam {
  /// The map's octree, to edit by hand.
  static octomap::OcTree& tree(GridMap& map) { return *map.tree_; }
};

/// Direct access to a grid-map explorer's map, for tests only.
struct GridExplorerTestSeam {
  /// The explorer's map, to edit by hand.
  static GridMap& map(GridExplorer& explorer) { return explorer.map_; }
  static GridMap& map(StarDiscoveryExplorer& explorer) { return explorer.map_; }
};

}  // namespace msb
