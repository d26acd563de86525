// The test seam of star discovery: its map, for hand-built scenes in tests (its octree through
// GridMapTestSeam, core/grid/grid_map_test_seam.h).
#pragma once

#include "core/grid/grid_map_test_seam.h"
#include "core/methods/star_discovery/star_discovery_explorer.h"

namespace msb {

/// Direct access to a star-discovery explorer's map, for tests only.
struct StarDiscoveryTestSeam {
  /// The explorer's map, to edit by hand.
  static GridMap& map(StarDiscoveryExplorer& explorer) { return explorer.map_; }
};

}  // namespace msb
