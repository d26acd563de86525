// A world description: ground, start pose, exploration box and object groups (fixed or
// randomly placed). Plain structs with validation; YAML is converted in tools/ only.
// Sizes drawn from ranges depend on the spec alone; placements depend on the seed, so a
// different seed moves objects without changing their counts or sizes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/config_check.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Object kinds the generator knows.
const std::vector<std::string>& worldObjectKinds();

/// A group of objects of one kind.
struct ObjectGroupSpec {
  std::string kind;  ///< building, tower, car, suv, bus, fire_truck, ambulance, tree, rod, pole, wall, rock, gazebo,
                     ///< house, pillar
  int count = 1;     ///< number of objects
  std::optional<Vec2> at;          ///< fixed position (count must be 1)
  std::optional<Vec2> region_min;  ///< random placement region (with region_max)
  std::optional<Vec2> region_max;
  std::optional<double> yaw_deg;  ///< fixed yaw; default random (region) or 0 (at)
  Vec3 size_min = Vec3::Zero();   ///< size range (kind-specific meaning, see docs/worlds.md)
  Vec3 size_max = Vec3::Zero();
  std::string variant;           ///< kind-specific: building burned|collapsed|collapsed_burned, ...
  std::string texture;           ///< texture override (default per kind)
  double tilt_max_deg = 0.0;     ///< random tilt (rods, poles, rocks)
  double burned_fraction = 0.4;  ///< burned share of a burned building's length (collapsed_burned: of its block)
  /// Look of the burned part: empty = flat black and textureless, else a texture name (e.g. the
  /// collapsed house's sooted brick, "burned").
  std::string burned_texture;
  double base_z_m = 0.0;  ///< height of the object's base
  /// "ruins": placed at the ruins built before (burned parts and collapsed buildings), not in a
  /// region — rods as reinforcement bars standing out of the ruins and their rubble.
  std::string near;

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A rectangular chamber of a cave, carved out of solid rock up to its ceiling height.
struct CaveChamberSpec {
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();
  double ceiling_m = 8.0;
};

/// A straight tunnel of a cave between two points.
struct CaveTunnelSpec {
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  double width_m = 6.0;
  double ceiling_m = 6.0;
};

/// An enclosed cave: everything inside [min, max] is rock except chambers and tunnels.
struct CaveSpec {
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();
  double rock_top_m = 20.0;  ///< height of the rock mass (ceiling top)
  double cell_m = 2.5;       ///< carving resolution
  std::vector<CaveChamberSpec> chambers;
  std::vector<CaveTunnelSpec> tunnels;
  std::string texture = "rock";
};

/// A whole world.
struct WorldSpec {
  std::string name;                     ///< world name (folder under worlds/)
  std::string description;              ///< one line for `world list`
  uint64_t seed = 1;                    ///< placement seed
  Vec2 ground_size_m = Vec2(120, 120);  ///< ground plane extent, centred on the origin
  std::string ground_texture = "grass";
  Vec3 start_position_m = Vec3::Zero();  ///< vehicle start (on the ground: z = 0)
  double start_yaw_deg = 0.0;
  Aabb exploration_box;            ///< where exploration goals may lie
  double start_clearance_m = 6.0;  ///< free radius kept around the start
  double start_corridor_m = 0.0;   ///< length of the free corridor along the start heading (take-off direction)
  double start_corridor_half_width_m = 3.0;  ///< its half width
  int texture_px = 512;                      ///< texture resolution
  std::vector<ObjectGroupSpec> objects;
  std::optional<CaveSpec> cave;

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

}  // namespace msb
