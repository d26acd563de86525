#include "core/explorer/method_registry.h"

#include <algorithm>
#include <stdexcept>

namespace msb {

namespace {
// Constructed on first use: registrars in other translation units run in any order.
std::vector<MethodRegistration>& registry() {
  static std::vector<MethodRegistration> methods;
  return methods;
}
}  // namespace

void addMethodRegistration(MethodRegistration r) {
  for (const auto& m : registry())
    if (m.info.type == r.info.type) throw std::logic_error("method type '" + r.info.type + "' is registered twice");
  registry().push_back(std::move(r));
}

std::vector<MethodRegistration> registeredMethods() {
  std::vector<MethodRegistration> out = registry();
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.info.type < b.info.type; });
  return out;
}

}  // namespace msb
