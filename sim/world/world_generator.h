// World generation: WorldSpec (+ seed) → MJCF text, texture list and ground-truth shapes.
// Deterministic: the same spec and seed give the same bytes.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/world_truth.h"
#include "sim/world/mesh_world.h"
#include "sim/world/world_spec.h"

namespace msb {

/// One object as placed: its id (kind_n), kind, source name (may be empty) and pose on the ground
/// (position before any `offset`, heading in degrees).
struct PlacedObject {
  std::string id, kind, name;
  Vec2 xy = Vec2::Zero();
  double yaw_deg = 0.0;
};

/// A generated world, before its files are written.
struct GeneratedWorld {
  std::string name;
  std::string paper_world;                            ///< the spec's paper_world ("" if none)
  std::string mjcf;                                   ///< world.xml text
  std::vector<std::string> textures;                  ///< pattern names to write as textures/<name>.png
  std::map<std::string, std::string> image_textures;  ///< imported images: name → PNG bytes (textures/<name>.png)
  std::vector<MeshBuildReport> meshes;                ///< what each imported mesh became
  std::vector<Shape> shapes;                          ///< ground truth, same names as the collision geoms
  Pose start = Pose::Identity();                      ///< vehicle start pose
  Aabb exploration_box;
  std::map<std::string, int> object_counts;  ///< objects per kind
  std::vector<PlacedObject> objects;         ///< every object, in build order
  int collision_geoms = 0, visual_geoms = 0;
};

/// Generates the world. Throws ConfigError for an invalid spec and std::runtime_error if
/// random placement cannot fit the requested objects.
GeneratedWorld generateWorld(const WorldSpec& spec);

/// Version of the generator; part of the cache key so cached worlds rebuild when it changes.
inline constexpr int kWorldGeneratorVersion =
    5;  // 2: skybox texture, 3: sun light, 4: sky planes, outdoor sun only, vehicles, 5: burned texture
        // (imported meshes need no new version: their vertices and image hashes are in the MJCF)

}  // namespace msb
