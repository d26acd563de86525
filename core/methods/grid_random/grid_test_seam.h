// The test seam of the grid explorer: its map, for hand-built scenes in tests (its octree through
// GridMapTestSeam, core/grid/grid_map_test_seam.h).
#pragma once

#include "core/grid/grid_map_test_seam.h"
#include "core/methods/grid_random/grid_explorer.h"

namespace msb {

/// Direct access to a grid explorer's map, for tests only.
struct GridExplorerTestSeam {
  /// The explorer's map, to edit by hand.
  static GridMap& map(GridExplorer& explorer) { return explorer.map_; }
};

}  // namespace msb
