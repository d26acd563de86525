#include "tools/loop/methods.h"

namespace msb {

MethodChoice monospheresMethod(const MonoSpheresConfig& config) {
  const MonoSpheresConfig c = checkValid(config);
  MethodChoice m;
  m.type = kMonoSpheresType;
  m.config = c;
  m.switches = {{"ovde", c.map.ovde}, {"dbof", c.map.dbof}, {"fff", c.planner.fff}, {"vpb", c.planner.viewpoints.vpb}};
  m.make = [c](const FisheyeCamera& camera, const ExplorerContext& context) {
    return std::make_unique<MonoSpheresExplorer>(c, camera, context);
  };
  return m;
}

MethodChoice gridRandomMethod(const GridExplorerConfig& config) {
  const GridExplorerConfig c = checkValid(config);
  MethodChoice m;
  m.type = kGridRandomType;
  m.config = c;
  m.switches = {{"unknown_is_occupied", c.planner.unknown_is_occupied}};
  m.make = [c](const FisheyeCamera&, const ExplorerContext& context) {
    return std::make_unique<GridExplorer>(c, context);
  };
  return m;
}

MethodChoice starDiscoveryMethod(const StarDiscoveryConfig& config) {
  const StarDiscoveryConfig c = checkValid(config);
  MethodChoice m;
  m.type = kStarDiscoveryType;
  m.config = c;
  m.switches = {{"unknown_is_occupied", c.planner.unknown_is_occupied}};
  m.make = [c](const FisheyeCamera&, const ExplorerContext& context) {
    return std::make_unique<StarDiscoveryExplorer>(c, context);
  };
  return m;
}

}  // namespace msb
