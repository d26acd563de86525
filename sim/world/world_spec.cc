#include "sim/world/world_spec.h"

#include <algorithm>

#include "sim/world/procedural_textures.h"

namespace msb {

const std::vector<std::string>& worldObjectKinds() {
  static const std::vector<std::string> kinds = {"building",   "tower",     "house",  "car",     "suv",  "bus",
                                                 "fire_truck", "ambulance", "tree",   "rod",     "pole", "wall",
                                                 "rock",       "gazebo",    "pillar", "dumpster"};
  return kinds;
}

void ObjectGroupSpec::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  const auto& kinds = worldObjectKinds();
  c.require(std::find(kinds.begin(), kinds.end(), kind) != kinds.end(), "kind", "unknown object kind '" + kind + "'");
  c.require(near.empty() || kind == "rod", "near", "placement at the ruins is for rods");
  c.require(
      near.empty() ? at.has_value() != (region_min.has_value() && region_max.has_value())
                   : !at.has_value() && !region_min && !region_max,
      "at",
      near.empty() ? "give either 'at' or 'region' (min and max)" : "'near' places the objects: no 'at' or 'region'");
  c.require(!at || count == 1, "count", "must be 1 with a fixed position 'at'");
  c.require(at || name.empty(), "name", "names a fixed object: give 'at'");
  c.require(at || offset.isZero(), "offset", "moves a fixed object's solid from 'at': give 'at'");
  if (region_min && region_max)
    c.require((region_max->array() > region_min->array()).all(), "region", "max must exceed min");
  c.require((size_max.array() >= size_min.array()).all() && size_max.maxCoeff() > 0, "size",
            "needs size_min <= size_max, not all zero");
  c.require(texture.empty() || isTextureName(texture), "texture", "unknown texture '" + texture + "'");
  c.require(burned_texture.empty() || isTextureName(burned_texture), "burned_texture",
            "unknown texture '" + burned_texture + "'");
  const bool variant_ok =
      variant.empty() ||
      (kind == "building" && (variant == "burned" || variant == "collapsed" || variant == "collapsed_burned"));
  c.require(variant_ok, "variant", "unknown variant '" + variant + "' for kind " + kind);
}

void CaveChamberSpec::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require((max.array() > min.array()).all(), "max", "must exceed min");
}

void CaveSpec::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require((max.array() > min.array()).all(), "max", "must exceed min");
  c.require(!chambers.empty(), "chambers", "needs at least one chamber");
  for (size_t i = 0; i < chambers.size(); ++i) {
    c.nested("chambers[" + std::to_string(i) + "]", chambers[i]);
    c.require(chambers[i].ceiling_m < rock_top_m, "chambers[" + std::to_string(i) + "].ceiling_m",
              "must be below rock_top_m");
  }
  for (size_t i = 0; i < tunnels.size(); ++i) {
    c.nested("tunnels[" + std::to_string(i) + "]", tunnels[i]);
    c.require(tunnels[i].ceiling_m < rock_top_m, "tunnels[" + std::to_string(i) + "].ceiling_m",
              "must be below rock_top_m");
  }
  c.require(isTextureName(texture), "texture", "unknown texture '" + texture + "'");
}

void SourceSpec::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(!repository.empty(), "repository", "is required (e.g. owner/name)");
  c.require(!commit.empty(), "commit", "is required (the commit the files were taken from)");
}

void MeshSpec::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  // A path inside the checkout: relative, without '..'.
  const bool inside = !file.empty() && file[0] != '/' && file.find("..") == std::string::npos;
  c.require(inside, "file", "must be a path inside the source checkout (relative, no '..'), got '" + file + "'");
  c.require(missing_texture.empty() || isTextureName(missing_texture), "missing_texture",
            "unknown texture '" + missing_texture + "'");
}

void WorldSpec::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(!name.empty(), "name", "is required");
  // A plain name: it becomes a directory of the world cache.
  c.require(
      name.size() <= 64 && name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") ==
                               std::string::npos,
      "name", "must be a plain name (letters, digits, '_' and '-', at most 64), got '" + name + "'");
  c.require(ground_size_m.minCoeff() >= 10 && ground_size_m.maxCoeff() <= 2000, "ground.size_m",
            "must be in [10, 2000] m");
  c.require(isTextureName(ground_texture), "ground.texture", "unknown texture '" + ground_texture + "'");
  c.require((exploration_box.max.array() > exploration_box.min.array()).all(), "exploration_box",
            "max must exceed min");
  c.require(texture_px == 128 || texture_px == 256 || texture_px == 512 || texture_px == 1024, "texture_px",
            "must be 128, 256, 512 or 1024");
  for (size_t i = 0; i < objects.size(); ++i) c.nested("objects[" + std::to_string(i) + "]", objects[i]);
  // Everything lies on the ground plane: positions inside its extent, sizes no larger than it.
  const Vec2 half = 0.5 * ground_size_m;
  auto onGround = [&](const Vec2& xy) { return (xy.array().abs() <= half.array() + 1e-9).all(); };
  c.require(onGround(start_position_m.head<2>()), "start.position",
            "must lie on the ground plane (within ground.size_m)");
  c.require(onGround(exploration_box.min.head<2>()) && onGround(exploration_box.max.head<2>()), "exploration_box",
            "must lie over the ground plane (within ground.size_m)");
  for (size_t i = 0; i < objects.size(); ++i) {
    const ObjectGroupSpec& o = objects[i];
    const std::string key = "objects[" + std::to_string(i) + "]";
    if (o.at) c.require(onGround(*o.at), key + ".at", "must lie on the ground plane (within ground.size_m)");
    if (o.region_min && o.region_max)
      c.require(onGround(*o.region_min) && onGround(*o.region_max), key + ".region",
                "must lie on the ground plane (within ground.size_m)");
    c.require(o.size_max.allFinite() && o.size_max.maxCoeff() <= ground_size_m.maxCoeff(), key + ".size",
              "must be no larger than the ground plane");
  }
  if (cave) c.nested("cave", *cave);
  c.require(meshes.empty() || source.has_value(), "source", "is required with meshes (where they come from)");
  if (source) c.nested("source", *source);
  for (size_t i = 0; i < meshes.size(); ++i) c.nested("meshes[" + std::to_string(i) + "]", meshes[i]);
}

}  // namespace msb
