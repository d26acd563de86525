// The registration of `method.type: python`: its keys (entry, path, budgets, params), listed
// after the paper's methods. Its explorer slot refuses to be built in the binary: the Python
// module builds the method from these keys (docs/python.md).
#include "core/methods/python/python_method.h"

#include <map>
#include <optional>

#include "core/common/config_check.h"
#include "core/explorer/method_registry.h"

namespace msb {

namespace {

// The explorer slot of a Python method: the C++ binary cannot build one (the Python module does).
class PythonMethodSlot final : public Explorer {
 public:
  PythonMethodSlot(const PythonMethodConfig&, const ExplorerContext&) {
    throw ConfigError("method.type",
                      "'python' methods run through the Python module: msbench run hands them to "
                      "/usr/bin/python3 -m msbench (docs/python.md)");
  }
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {}; }
};

}  // namespace

/// Registered before main() (the library is linked whole: docs/architecture.md); listed right
/// after the paper's three methods.
const MethodRegistrar kPythonMethod = registerMethod<PythonMethodSlot, PythonMethodConfig>(
    {"python",
     "a method written in Python (method.entry: \"package.module:factory\"; docs/python.md)",
     {},
     {},
     /*listed=*/3});

}  // namespace msb
