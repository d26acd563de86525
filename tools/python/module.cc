// The Python module `msbench._msbench` (docs/python.md): the loop library and the configuration
// layer the command line uses, bound with pybind11 — no second loop, no second configuration
// path. Scenario.load is loadScenario; Mission is the tools/engine Mission; write() writes the files
// `msbench run` writes (tools/results). The GIL is released while C++ steps the loop; Ctrl-C is
// checked between simulated seconds. Each bound area is its own file (binding.h).
#include "tools/config/world_registry.h"
#include "tools/python/binding.h"

PYBIND11_MODULE(_msbench, m) {
  m.doc() = "msbench: deterministic closed-loop benchmark for monocular UAV exploration (docs/python.md)";
  msb::binding::bindErrors(m);
  msb::binding::bindScenarioAndTicks(m);
  msb::binding::bindMethodTypes(m);
  msb::binding::bindMission(m);
  m.attr("__version__") = MSB_VERSION;
  m.attr("worlds_dir") = msb::worldsDir();  // what a confined method may not read (msbench.confined)
}
