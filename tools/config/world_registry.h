// Finding, loading and building worlds by name for the CLI: worlds/<name>/spec.yaml (generated,
// cached) or worlds/<name>/world.xml (hand-written MJCF), or any MJCF file path.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/geometry/world_truth.h"
#include "sim/world/world_cache.h"
#include "tools/engine/flight_spec.h"
#include "tools/engine/scenario_spec.h"

namespace msb {

/// The worlds directory: $MSBENCH_WORLDS_DIR or the source tree's worlds/.
std::string worldsDir();
/// The generated-world cache: $MSBENCH_CACHE_DIR or <worlds dir>/.cache.
std::string worldCacheDir();
/// The runs msbench publishes (its own settings, docs/metrics.md): $MSBENCH_RESULTS_DIR or the
/// source tree's results/.
std::string resultsDir();
/// Where `msbench world import NAME` keeps a world's imported source files: the cache's
/// sources/NAME/.
std::string worldSourcesDir(const std::string& name);

/// A world known by name.
struct WorldEntry {
  std::string name;
  std::string description;
  std::string path;  ///< spec.yaml or world.xml
  bool generated;    ///< true for spec.yaml worlds
};

/// All worlds in the worlds directory, sorted by name.
std::vector<WorldEntry> listWorlds();

/// Loads and validates a world spec file (the YAML layer). Throws FileConfigError.
WorldSpec loadWorldSpec(const std::string& path);

/// A world ready to load into the simulator.
struct ResolvedWorld {
  std::string world_xml;            ///< MJCF path
  std::optional<BuiltWorld> built;  ///< generated worlds: shapes, start, box, counts
};

/// Resolves a world argument (name or MJCF path); generated worlds are built into the cache
/// with the spec's seed or `seed` if given. Throws UsageError (listing the names that exist)
/// for an unknown world.
ResolvedWorld resolveWorld(const std::string& arg, std::optional<uint64_t> seed = std::nullopt,
                           const std::string& salt = "");

/// Largest salt file read (bytes): a salt is one line of a few dozen characters.
inline constexpr size_t kMaxSaltFileBytes = 4096;

/// The evaluator's salt for held-out worlds: $MSBENCH_WORLD_SALT, else the first line of the file
/// $MSBENCH_WORLD_SALT_FILE names (a regular file of at most kMaxSaltFileBytes, opened without
/// blocking: InputFileError, exit 2, otherwise). Throws std::runtime_error naming both when
/// neither gives a salt of at least kMinSaltChars characters.
std::string heldOutSalt();

/// Resolves the world named in flight file `file` (spec.world_name, if any) into
/// spec.world_path; an unknown name is a FileConfigError naming the file and key.
std::optional<BuiltWorld> resolveFlightWorld(const std::string& file, FlightSpec& spec);

/// A mission's world as the runner needs it: the exploration box and, for generated worlds,
/// the ground truth.
struct MissionWorld {
  Aabb box;                         ///< the scenario's box, else the world's, else unbounded
  std::optional<WorldTruth> truth;  ///< generated worlds only
};

/// Resolves the scenario's world (resolveFlightWorld), sets the start pose from a generated
/// world when the scenario asks for it, and returns the box and the ground truth.
MissionWorld prepareMissionWorld(const std::string& file, ScenarioSpec& spec);

}  // namespace msb
