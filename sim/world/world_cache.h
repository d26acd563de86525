// Builds generated worlds into an on-disk cache (MJCF + PNG textures + shapes.csv), keyed by
// name, seed and a hash of the generated content, so repeated runs reuse them. Directories are
// written under a temporary name and renamed: parallel runs never see half-written worlds.
#pragma once

#include <string>

#include "sim/world/world_generator.h"
#include "sim/world/world_salt.h"

namespace msb {

/// A world ready for the simulator.
struct BuiltWorld {
  std::string world_xml;       ///< path of the MJCF file
  std::string directory;       ///< its cache directory
  GeneratedWorld generated;    ///< shapes, start, exploration box, counts
  bool reused = false;         ///< found in the cache
  double build_seconds = 0.0;  ///< wall time of generation (+ writing, if built)
  WorldSalting salting;        ///< how a held-out world differs from its spec (none: not held out)
};

/// Generates `spec` and makes sure its files exist under `cache_root`. Throws on I/O errors.
BuiltWorld buildWorld(const WorldSpec& spec, const std::string& cache_root);

}  // namespace msb
