#include "core/explorer/method_registry.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace msb {

namespace {
// Constructed on first use: registrars in other translation units run in any order.
std::vector<MethodRegistration>& registry() {
  static std::vector<MethodRegistration> methods;
  return methods;
}
// What was wrong with the registrations, one line each (reported when the registry is used).
std::vector<std::string>& problems() {
  static std::vector<std::string> lines;
  return lines;
}
// The names of a method's keys under `method:` (its top level only).
class TopLevelKeys final : public KeyVisitor {
 public:
  std::vector<std::string> names;
  void key(const char* n, double&, const Limits&) override { names.push_back(n); }
  void key(const char* n, int&, const Limits&) override { names.push_back(n); }
  void key(const char* n, uint64_t&, const Limits&) override { names.push_back(n); }
  void key(const char* n, Vec2&, const Limits&) override { names.push_back(n); }
  void key(const char* n, Vec3&, const Limits&) override { names.push_back(n); }
  void key(const char* n, std::array<double, 3>&, const Limits&) override { names.push_back(n); }
  void key(const char* n, std::array<double, 4>&, const Limits&) override { names.push_back(n); }
  void key(const char* n, bool&) override { names.push_back(n); }
  void key(const char* n, std::string&) override { names.push_back(n); }
  void key(const char* n, std::string&, const Choices&) override { names.push_back(n); }
  void key(const char* n, MapText&) override { names.push_back(n); }
  void group(const char* n, const std::function<void(KeyVisitor&)>&) override { names.push_back(n); }
  void moved(const char* n, const char*) override { names.push_back(n); }
  void preset(const char* n, const PresetKey&) override { names.push_back(n); }
};

// True if `name` is letters, digits and '_', and not empty.
bool wellFormedName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(),
                                      [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// What is wrong with the hooks a method offers ("" = nothing): a malformed name, one name twice.
std::string hookProblem(const MethodInfo& info) {
  for (size_t i = 0; i < info.hooks.size(); ++i) {
    const std::string& name = info.hooks[i].name;
    if (!wellFormedName(name) || !info.hooks[i].hook)
      return "method '" + info.type + "' offers a hook named '" + name +
             "': a hook needs a name of letters, digits and '_' and a function";
    for (size_t j = 0; j < i; ++j)
      if (info.hooks[j].name == name) return "method '" + info.type + "' offers the hook '" + name + "' twice";
  }
  return "";
}

// The keys every `method:` section has besides the method's own.
constexpr const char* kSharedMethodKeys[] = {"type"};
}  // namespace

void addMethodRegistration(MethodRegistration r) noexcept {
  try {
    const std::string& type = r.info.type;
    if (!wellFormedName(type)) {
      problems().push_back(r.source_file + ": method type '" + type +
                           "' must be letters, digits and '_' (and not empty)");
      return;
    }
    if (const std::string why = hookProblem(r.info); !why.empty()) {
      problems().push_back(r.source_file + ": " + why);
      return;
    }
    // A key of the method's that is a key every method: section has (`method.type`).
    TopLevelKeys keys;
    std::any config = r.default_config();
    r.keys(config, keys);
    for (const std::string& k : keys.names)
      for (const char* shared : kSharedMethodKeys)
        if (k == shared) {
          problems().push_back(r.source_file + ": method '" + type + "' has a key named '" + k +
                               "', which every method: section has (method." + k + "); rename the key");
          return;
        }
    for (const auto& m : registry())
      if (m.info.type == type) {
        problems().push_back("method type '" + type + "' is registered twice: in " + m.source_file + " and in " +
                             r.source_file + "; rename one");
        return;
      }
    registry().push_back(std::move(r));
  } catch (...) {
    // Out of memory before main(): nothing sensible to do but leave the method out.
  }
}

std::vector<MethodRegistration> registeredMethods() {
  if (!problems().empty()) {
    std::string all;
    for (const auto& p : problems()) all += (all.empty() ? "" : "\n") + p;
    throw MethodRegistryError(all);
  }
  std::vector<MethodRegistration> out = registry();
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.info.type < b.info.type; });
  return out;
}

}  // namespace msb
