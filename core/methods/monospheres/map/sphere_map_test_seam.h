// The test seam of SphereMap: hand-built maps for tests. The mapper builds its map from frames
// alone, so these edits are not on SphereMap's public interface; tests reach them here, by name.
#pragma once

#include <cstdint>
#include <optional>

#include "core/methods/monospheres/map/sphere_map.h"

namespace msb {

/// Direct edits of a SphereMap, for tests only.
struct SphereMapTestSeam {
  /// Adds a sphere; returns its id. Links it into the graph.
  static uint64_t addSphere(SphereMap& m, const Vec3& centre, double radius) { return m.addSphere(centre, radius); }
  /// Adds an obstacle point with its measurement distance; returns its id.
  static uint64_t addObstacle(SphereMap& m, const Vec3& p, double d_min) { return m.addObstacle(p, d_min); }
  /// Step 8 on one sphere; returns true if it was removed.
  static bool sparsify(SphereMap& m, uint64_t id) { return m.sparsify(id); }
  /// Step 9 on one measured point; returns true if kept.
  static bool insertObstacle(SphereMap& m, const Vec3& p, double distance_from_camera) {
    return m.insertObstacle(p, distance_from_camera);
  }
  /// Removes an obstacle point (as DBOF does).
  static void eraseObstacle(SphereMap& m, uint64_t id) { m.eraseObstacle(id); }
  /// Adds a frontier at x if it passes the frontier test; returns its id.
  static std::optional<uint64_t> tryAddFrontier(SphereMap& m, const Vec3& x) { return m.tryAddFrontier(x); }
  /// Drops every frontier that is no longer valid; returns how many.
  static int revalidateFrontiers(SphereMap& m) { return m.revalidateFrontiers(); }
  /// Re-validates the frontiers near what changed since the last update; returns how many dropped.
  static int revalidateChangedFrontiers(SphereMap& m) { return m.revalidateChangedFrontiers(); }
};

}  // namespace msb
