#include "tools/engine/methods.h"

#include <algorithm>
#include <stdexcept>

namespace msb {

const std::vector<MethodRegistration>& methodRegistrations() {
  static const std::vector<MethodRegistration> registered = [] {
    std::vector<MethodRegistration> r = registeredMethods();
    std::stable_sort(r.begin(), r.end(), [](const auto& a, const auto& b) { return a.info.listed < b.info.listed; });
    return r;
  }();
  return registered;
}

const MethodRegistration* findRegistration(const std::string& type) {
  for (const auto& reg : methodRegistrations())
    if (reg.info.type == type) return &reg;
  return nullptr;
}

MethodChoice registeredMethodChoice(const MethodRegistration& reg, std::any config) {
  MethodChoice choice;
  choice.type = reg.info.type;
  const MethodFacts facts = reg.facts(config);
  choice.switches = facts.switches;
  choice.reference_code = facts.reference_code;
  choice.octree_resolution_m = facts.octree_resolution_m;
  choice.hooks = reg.info.hooks;
  choice.make = [&reg, config](const FisheyeCamera& camera, const ExplorerContext& context) {
    return reg.make(config, camera, context);
  };
  choice.config = std::move(config);
  return choice;
}

MethodChoice defaultMethod() {
  const MethodRegistration* reg = findRegistration(kDefaultMethodType);
  if (!reg)
    throw std::logic_error(std::string("the default method '") + kDefaultMethodType +
                           "' is not linked into this program (link the method libraries whole, tools/CMakeLists.txt)");
  return registeredMethodChoice(*reg, reg->default_config());
}

}  // namespace msb
