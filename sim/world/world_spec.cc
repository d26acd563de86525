#include "sim/world/world_spec.h"

#include <algorithm>

#include "sim/world/procedural_textures.h"

namespace msb {

const std::vector<std::string>& worldObjectKinds() {
  static const std::vector<std::string> kinds = {"building", "tower",      "house",     "car",    "suv",
                                                 "bus",      "fire_truck", "ambulance", "tree",   "rod",
                                                 "pole",     "wall",       "rock",      "gazebo", "pillar"};
  return kinds;
}

void ObjectGroupSpec::validate(ConfigChecker& c) const {
  const auto& kinds = worldObjectKinds();
  c.require(std::find(kinds.begin(), kinds.end(), kind) != kinds.end(), "kind", "unknown object kind '" + kind + "'");
  c.require(count >= 1 && count <= 1000, "count", "must be in [1, 1000]");
  c.require(near.empty() || near == "ruins", "near", "unknown placement '" + near + "' (known: ruins)");
  c.require(near.empty() || kind == "rod", "near", "placement at the ruins is for rods");
  c.require(
      near.empty() ? at.has_value() != (region_min.has_value() && region_max.has_value())
                   : !at.has_value() && !region_min && !region_max,
      "at",
      near.empty() ? "give either 'at' or 'region' (min and max)" : "'near' places the objects: no 'at' or 'region'");
  c.require(!at || count == 1, "count", "must be 1 with a fixed position 'at'");
  if (region_min && region_max)
    c.require((region_max->array() > region_min->array()).all(), "region", "max must exceed min");
  c.require((size_min.array() >= 0).all() && (size_max.array() >= size_min.array()).all() && size_max.maxCoeff() > 0,
            "size", "needs 0 <= size_min <= size_max, not all zero");
  c.require(texture.empty() || isTextureName(texture), "texture", "unknown texture '" + texture + "'");
  c.inRange("tilt_max_deg", tilt_max_deg, 0.0, 60.0);
  c.inRange("burned_fraction", burned_fraction, 0.05, 0.95);
  c.require(burned_texture.empty() || isTextureName(burned_texture), "burned_texture",
            "unknown texture '" + burned_texture + "'");
  const bool variant_ok =
      variant.empty() ||
      (kind == "building" && (variant == "burned" || variant == "collapsed" || variant == "collapsed_burned"));
  c.require(variant_ok, "variant", "unknown variant '" + variant + "' for kind " + kind);
}

void WorldSpec::validate(ConfigChecker& c) const {
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
  c.nonNegative("start_clearance_m", start_clearance_m);
  c.nonNegative("start_corridor_m", start_corridor_m);
  c.positive("start_corridor_half_width_m", start_corridor_half_width_m);
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
  if (cave) {
    c.require((cave->max.array() > cave->min.array()).all(), "cave", "max must exceed min");
    c.require(!cave->chambers.empty(), "cave.chambers", "needs at least one chamber");
    c.inRange("cave.cell_m", cave->cell_m, 0.5, 10.0);
    c.require(isTextureName(cave->texture), "cave.texture", "unknown texture '" + cave->texture + "'");
    for (const auto& ch : cave->chambers)
      c.require(ch.ceiling_m > 2.0 && ch.ceiling_m < cave->rock_top_m, "cave.chambers",
                "ceiling_m must be in (2, rock_top_m)");
    for (const auto& t : cave->tunnels)
      c.require(t.width_m >= 2.0 && t.ceiling_m > 2.0 && t.ceiling_m < cave->rock_top_m, "cave.tunnels",
                "width_m >= 2 and ceiling_m in (2, rock_top_m)");
  }
}

}  // namespace msb
