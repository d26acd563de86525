// A world's imported meshes (WorldSpec::meshes) built into its MJCF and ground truth: each node's
// convex pieces as hidden collision geoms and truth shapes, each surface as a visual mesh with
// its material's image (grey, scaled down to max_texture_px), or, where the image is absent from
// the imported source, the spec's procedural `missing_texture` laid in world metres.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "sim/world/mesh_import.h"
#include "sim/world/mjcf_world_builder.h"
#include "sim/world/world_spec.h"

namespace msb {

/// What one imported mesh became.
struct MeshBuildReport {
  std::string file;
  size_t triangles = 0;
  std::vector<std::pair<std::string, std::string>> nodes;  ///< (node, "rule, N pieces")
  std::vector<std::string> images;                         ///< images drawn, as the file names them
  std::vector<std::string> stand_ins;                      ///< images absent, drawn as missing_texture
};

/// Builds `spec.meshes` into `b` from `spec.source_dir`; their images go to `images` (texture
/// name → PNG bytes). Throws ConfigError naming `meshes[i].file` (and how to import it) when a
/// file is missing, cannot be read, or names an absent image without a missing_texture.
std::vector<MeshBuildReport> buildMeshes(const WorldSpec& spec, MjcfWorldBuilder& b,
                                         std::map<std::string, std::string>& images);

/// The files of `spec.meshes` inside the source checkout and the images they name (relative
/// to the checkout; images that are absent are listed in `missing`). Used by `world import`.
std::vector<std::string> meshSourceFiles(const WorldSpec& spec, const std::string& checkout,
                                         std::vector<std::string>& missing);

}  // namespace msb
