// Held-out worlds (docs/worlds.md, "Held-out worlds"): a world drawn at evaluation time from its
// spec and a salt the evaluator supplies, so that no method can carry its truth in advance.
// Deterministic: the same spec and salt give the same world, byte for byte.
#pragma once

#include <cstdint>
#include <string>

#include "core/common/aabb.h"
#include "sim/world/world_spec.h"

namespace msb {

/// How a salted world differs from its spec as a whole: a mirror across the vertical plane
/// through the start along its heading (or none), applied to everything the world places.
struct WorldSalting {
  bool mirrored = false;
  Vec2 origin = Vec2::Zero();     ///< the start, on the mirror line
  Vec2 heading = Vec2::UnitX();   ///< the start's heading, the mirror line's direction
  uint64_t texture_seed = 0;      ///< the procedural textures' seed (0: the unsalted textures)
  int swapped = 0, jittered = 0;  ///< objects moved to a like object's place; poses jittered

  /// A point of the plan view as the salted world places it.
  Vec2 point(const Vec2& p) const;
  /// A heading (rad) as the salted world places it.
  double yaw(double yaw_rad) const;
  /// An axis-aligned box as the salted world places it (the start's heading is along an axis
  /// whenever `mirrored`, so the box stays axis-aligned).
  Aabb box(const Aabb& b) const;
};

/// The rules (docs/worlds.md): the world keeps its kinds, counts, sizes, start, exploration box
/// volume and start clearance. Objects placed at random are placed with a seed drawn from the
/// salt; fixed objects trade places with objects of the same kind and size, are moved by up to
/// `kSaltJitterM` and turned (buildings and houses by quarter turns, vehicles and walls by up to
/// kVehicleTurnDeg, the rest freely) — except on a terrain mesh (their heights are the terrain's)
/// and within kSaltKeepM of the start;
/// the whole world is mirrored across the start's heading line with probability 1/2 when that
/// heading lies along an axis; procedural textures take a seed drawn from the salt.
WorldSpec saltWorldSpec(const WorldSpec& spec, const std::string& salt, WorldSalting* how = nullptr);

/// The furthest a fixed object's position moves (m).
inline constexpr double kSaltJitterM = 1.5;

/// Fixed objects whose footprint comes within this distance of the start keep their place and
/// pose (up to the mirror): the take-off and its first minute are the world's own.
inline constexpr double kSaltKeepM = 10.0;

/// How far vehicles, walls and dumpsters turn (either way, degrees).
inline constexpr double kVehicleTurnDeg = 20.0;

/// The fewest characters a salt may have (a short salt can be guessed).
inline constexpr size_t kMinSaltChars = 16;

/// What a record carries instead of the salt: "fnv1a64:" and 16 hexadecimal digits of a
/// domain-separated hash. Equal salts give equal commitments; it says whether runs shared a salt,
/// and checks a salt revealed later (it is not a cryptographic commitment: see docs/worlds.md).
std::string worldSaltCommitment(const std::string& salt);

}  // namespace msb
