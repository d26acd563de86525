// hover_turn's registration: the one line that makes it a method msbench knows (method.type:
// hover_turn), with its config's keys, its explorer and the counters its progress line shows.
#include "core/explorer/method_registry.h"
#include "core/methods/hover_turn/hover_turn_explorer.h"

namespace msb {

/// Registered before main() (the library is linked whole: docs/architecture.md).
const MethodRegistrar kHoverTurnMethod = registerMethod<HoverTurnExplorer, HoverTurnConfig>(
    {"hover_turn",
     "example method: take off, turn once, descend (a template for new methods)",
     {"turn_steps", "points_seen"}});

}  // namespace msb
