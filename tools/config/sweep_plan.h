// A sweep: a base scenario plus a matrix of axes and seeds, expanded into an ordered list of
// runs with stable, readable ids (docs/sweeps.md). The YAML is read here (tools/ only).
//
//   scenario: ../missions/urban.yaml     # base scenario, relative to the sweep file
//   set: {duration_s: 600}               # overrides for every run (key path: value)
//   axes:                                # in order; the id joins the axes' labels
//     - {name: world, key: world, values: [urban, cave]}
//     - name: variant
//       variants:                        # label: overrides (key path: value); the special
//         full: {}                       # key `scenario` replaces the base scenario file
//         no_ovde: {method.switches.ovde: false}
//   seeds: [1, 2, 3]                     # or a count: 3 means 1, 2, 3
//   exclude: [{world: cave, variant: no_ovde}, {world: cave, seed: 3}]   # left out (labels
//   include: [...]                        # per axis, and/or a seed); if given, only these
//
// Runs are ordered axis by axis (the first axis slowest), then by seed; run id =
// "<label>-<label>-...-s<seed>" (e.g. urban-no_ovde-s2).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace msb {

/// One run of a sweep: `msbench run <scenario> --seed <seed> --set k=v ...`.
struct SweepRun {
  std::string id;        ///< stable, readable, unique
  std::string scenario;  ///< scenario file (absolute)
  uint64_t seed = 1;
  std::vector<std::pair<std::string, std::string>> sets;  ///< key path → YAML value, in order
  std::map<std::string, std::string> labels;              ///< axis name → label
};

/// An expanded sweep.
struct SweepPlan {
  std::string file;               ///< the sweep file
  std::string file_hash;          ///< FNV-1a of its bytes (changes are detected on resume)
  std::vector<std::string> axes;  ///< axis names in order
  std::vector<SweepRun> runs;     ///< in run order
};

/// Reads and expands a sweep file. Throws FileConfigError naming the file and key.
SweepPlan loadSweepPlan(const std::string& path);

}  // namespace msb
