// A method written in Python (docs/python.md): where its factory is and the keys it is given.
// The C++ binary embeds no Python, so `msbench run` hands such a scenario to the Python module,
// which builds the method from these and runs the same loop. A scenario's `goals:` section (an
// outside goal chooser written in Python) names its code the same way.
#pragma once

#include <string>

#include "core/common/config_check.h"
#include "core/common/config_fields.h"

namespace msb {

/// The `method.type` of a method written in Python.
inline constexpr char kPythonMethodType[] = "python";

/// Where a method (or a goal chooser) written in Python is, and what it is given.
struct PythonMethodConfig {
  std::string entry;               ///< "package.module:factory"
  std::string path;                ///< a directory put first on sys.path (relative: to the scenario file)
  MapText params;                  ///< the method's own keys (a YAML map), the factory's keyword arguments
  double call_budget_s = 60.0;     ///< wall-clock seconds each call of its process may take (a method only)
  double memory_limit_mib = 4096;  ///< its process's address space (RLIMIT_AS; a method only)

  /// A method's keys, each once (a goal chooser reads entry, path and params only).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("entry", s.entry);
    v.key("path", s.path);
    v.key("call_budget_s", s.call_budget_s, Limits::range(0.1, 86400.0));
    v.key("memory_limit_mib", s.memory_limit_mib, Limits::range(256.0, 1048576.0));
    v.key("params", s.params);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const {
    checkFields(*this, c);
    const auto colon = entry.find(':');
    c.require(colon != std::string::npos && colon > 0 && colon + 1 < entry.size() &&
                  entry.find(':', colon + 1) == std::string::npos,
              "entry", "must be \"package.module:factory\", got '" + entry + "'");
  }
};

}  // namespace msb
