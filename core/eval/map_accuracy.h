// The accuracy of a method's final map against the ground truth (metrics.json → map_accuracy):
// obstacle elements (points, occupied cells) within 0.5 m of a true surface; free elements
// (spheres, free cells) whose centre lies outside every obstacle; and, over each free element's
// whole extent, the declared free space that is falsely free: sampled on an 8 × 8 × 8 lattice
// over the element, a sample more than 0.5 m inside an obstacle is falsely free (the same band
// as the obstacles' "near a surface"). In the map's own frame (the VIO estimate), so drift counts
// against it.
#pragma once

#include <cstddef>
#include <optional>

#include "core/explorer/snapshot.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Counts of a map against the truth.
struct MapAccuracy {
  size_t obstacles = 0, obstacles_near_surface = 0;
  size_t free_elements = 0, free_really_free = 0;
  size_t free_elements_falsely_free = 0;  ///< elements with a sample more than 0.5 m inside an obstacle
  double free_volume_m3 = 0;              ///< declared free volume (elements summed, overlaps counted twice)
  double falsely_free_volume_m3 = 0;      ///< of it, the part more than 0.5 m inside obstacles

  /// obstacles_near_surface / obstacles (nullopt: no obstacle).
  std::optional<double> nearSurfaceShare() const;
  /// free_really_free / free_elements (nullopt: no free element).
  std::optional<double> reallyFreeShare() const;
  /// falsely_free_volume_m3 / free_volume_m3 (nullopt: no free volume).
  std::optional<double> falselyFreeVolumeShare() const;
  /// free_elements_falsely_free / free_elements (nullopt: no free element).
  std::optional<double> falselyFreeElementShare() const;
};

/// Where obstacle points lie against the truth (signed distance d to the nearest surface): inside
/// an obstacle (d < -0.5 m: behind the surface seen), near a surface (|d| <= 0.5 m) or floating
/// in free space (d > 0.5 m: the wrong points that take free space away); floating_far counts
/// the floating points more than 2 m from every surface (in the open, not just before a wall).
struct PointPlacement {
  size_t inside = 0, near_surface = 0, floating = 0;
  size_t floating_far = 0;  ///< of `floating`, those with d > 2 m

  /// All points counted.
  size_t total() const { return inside + near_surface + floating; }
};

/// Where one point lies against the truth (the classes of PointPlacement).
enum class Placement { inside, near_surface, floating_near, floating_far };

/// The placement of one point: inside (d < -0.5 m), near a surface (|d| <= 0.5 m), floating
/// within 2 m of a surface, floating farther.
Placement placementOf(const WorldTruth& truth, const Vec3& p);

/// Adds one point of the given placement to the counts.
void countPlacement(PointPlacement& counts, Placement placement);

/// How much of one free element (estimate frame) is falsely free: its volume and the part of it
/// more than `tolerance_m` inside obstacles (8 × 8 × 8 lattice over the element).
struct ElementFalseFree {
  double volume_m3 = 0, falsely_free_m3 = 0;
};
ElementFalseFree elementFalseFree(const FreeSpaceElement& e, const WorldTruth& truth, double tolerance_m = 0.5);

/// The map's accuracy (nullopt for an empty map).
std::optional<MapAccuracy> mapAccuracy(const ExplorerSnapshot& map, const WorldTruth& truth);

}  // namespace msb
