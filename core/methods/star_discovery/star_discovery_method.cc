// Star discovery's registration (von Stumberg et al., the related work's monocular explorer):
// method.type star_discovery, its table, the counters its progress line shows and its hook
// (its OctoMap as .bt, "octomap_binary").
#include "core/explorer/method_registry.h"
#include "core/methods/star_discovery/star_discovery_explorer.h"

namespace msb {

/// Registered before main() (the library is linked whole: docs/architecture.md).
const MethodRegistrar kStarDiscoveryMethod = registerMethod<StarDiscoveryExplorer, StarDiscoveryConfig>(
    {"star_discovery",
     "star discovery (von Stumberg et al.): look-around, star flights, interesting cells",
     {"leaves", "stars", "interesting_cells", "goals_reached"},
     {},
     /*listed=*/2,
     {{"octomap_binary", hookOf(&StarDiscoveryExplorer::octomapBinary)}}});

}  // namespace msb
