// The test seam of the grid map: its OctoMap, for hand-built scenes in tests. The map is built
// from frames alone; tests reach its tree here, by name.
#pragma once

#include "core/grid/grid_map.h"

namespace msb {

/// Direct access to a grid map's octree, for hand-built maps in tests only.
struct GridMapTestSeam {
  /// The map's octree, to edit by hand.
  static octomap::OcTree& tree(GridMap& map) { return *map.tree_; }
};

}  // namespace msb
