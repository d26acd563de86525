// Loading scenario files for `msbench run` (docs/architecture.md §12): an optional `base:` file (relative
// to the including file) whose keys the file overrides map by map, then command-line overrides
// `--set a.b.c=value` (the value is parsed as YAML), then the strict reader: unknown keys, wrong
// types and bad values fail with the file and the key named.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/methods/monospheres/map/sphere_map.h"
#include "tools/config/yaml_writer.h"
#include "tools/engine/scenario_spec.h"

namespace msb {

/// The scenario file `name` names from a file in `dir` (`base:`, a sweep's `scenario:`): `dir /
/// name`, or, for a bare name (no directory, no extension) that is no file there, the mission
/// scenarios/missions/<name>.yaml (`base: base`, `scenario: monospheres`). Not checked to exist.
std::filesystem::path scenarioFileNamed(const std::filesystem::path& dir, const std::string& name);

/// Loads and validates a scenario. Throws FileConfigError / UsageError.
ScenarioSpec loadScenario(const std::string& path, const std::vector<std::string>& sets = {});

/// Mapper settings for map-replay from `--set map.KEY=VALUE` overrides, through the same
/// override path and reader as a scenario's `method.map` keys (plus the switches map.ovde and
/// map.dbof). Throws UsageError (malformed --set) or FileConfigError (unknown key, bad value).
SphereMapConfig loadMapOverrides(const std::vector<std::string>& sets);

/// The effective configuration of a loaded scenario as YAML text (what config.yaml records):
/// every key with its value, defaults included, numbers in their shortest exact form, so that
/// loading the text gives the same ScenarioSpec (and running it the same run). The world is
/// written as named (a world name, or the MJCF file with its absolute path); `start` only if
/// the scenario gave one (else the generated world's start applies).
/// With `log`, each key's accepted values are also recorded there (`msbench keys`).
std::string effectiveScenarioYaml(const ScenarioSpec& spec, std::shared_ptr<MapWriter::KeyLog> log = nullptr);

/// The benchmark's side of a scenario (docs/metrics.md, "Fixed settings"): the effective YAML
/// without what a method or a run chooses — `name`, `suite`, `seed`, `method`, `goals`, `video`,
/// `mission.progress`, `mission.write_map_ply`. Two runs with the same text flew the same world,
/// duration, vehicle, speed set, camera, front end, rates and box.
std::string fixedSettingsYaml(const ScenarioSpec& spec);
/// FNV-1a 64 of fixedSettingsYaml(), 16 hex digits (metrics.json `fixed_settings_hash`).
std::string fixedSettingsHash(const ScenarioSpec& spec);
/// What a charged run's latency log was measured under (its header's `scenario`): FNV-1a 64 of
/// the effective YAML without `name`, `suite`, `seed` (checked on its own), `video`,
/// `timing.replay`, `mission.progress` and `mission.write_map_ply`, 16 hex digits. A log replays
/// only into a run of the same hash and seed.
std::string replaySettingsHash(const ScenarioSpec& spec);

}  // namespace msb
