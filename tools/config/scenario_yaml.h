// Loading scenario files for `msbench run` (docs/architecture.md §12): an optional `base:` file (relative
// to the including file) whose keys the file overrides map by map, then command-line overrides
// `--set a.b.c=value` (the value is parsed as YAML), then the strict reader: unknown keys, wrong
// types and bad values fail with the file and the key named.
#pragma once

#include <string>
#include <vector>

#include "core/map/sphere_map.h"
#include "tools/loop/scenario_spec.h"

namespace msb {

/// Loads and validates a scenario. Throws FileConfigError / UsageError.
ScenarioSpec loadScenario(const std::string& path, const std::vector<std::string>& sets = {});

/// Mapper settings for map-replay from `--set map.KEY=VALUE` overrides, through the same
/// override path and reader as a scenario's `method.map` keys (plus the switches map.ovde and
/// map.dbof). Throws UsageError (malformed --set) or FileConfigError (unknown key, bad value).
SphereMapConfig loadMapOverrides(const std::vector<std::string>& sets);

/// The merged tree of a scenario file and its base chain with the `--set` overrides applied, as
/// YAML text (what config.yaml records). Relative MJCF world paths are made absolute against the
/// file that names them. Throws FileConfigError (file problems) or UsageError (malformed --set).
std::string mergedScenarioYaml(const std::string& path, const std::vector<std::string>& sets = {});

}  // namespace msb
