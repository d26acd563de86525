// A convex polytope in the world frame: the solid pieces an imported mesh is cut into (a terrain
// triangle down to a floor, a thin slab under a surface triangle, a convex part whole). MuJoCo
// collides a mesh geom as the convex hull of its vertices; this is the same hull for the ground
// truth, with exact signed distance and ray intersection.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// A convex polytope: its vertices, its surface triangles (outward winding) and its face planes.
struct ConvexPolytope {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< surface, counter-clockwise seen from outside
  /// Face planes (unit outward normal n, offset d): a point p is inside when n·p − d ≤ 0 for all.
  std::vector<std::pair<Vec3, double>> planes;

  /// Signed distance from p to the surface (negative inside; exact inside and outside).
  double signedDistance(const Vec3& p) const;
  /// Distance along the unit ray o + t d to the first surface point (t ≥ 0; 0 if o is inside).
  std::optional<double> raycast(const Vec3& o, const Vec3& d) const;
  /// Axis-aligned bounds (min, max) of the vertices.
  std::pair<Vec3, Vec3> bounds() const;
};

/// The convex solid that `triangles` over `vertices` bound, if they do: a closed surface (every
/// edge shared by two triangles) with every vertex on or behind every triangle's plane (within
/// `tolerance_m`) and a volume of at least `min_volume_m3`. Triangles are turned to face
/// outwards (away from the centroid) and coplanar ones share one plane. Degenerate triangles
/// (area below 1e-12 m²) are dropped first.
std::optional<ConvexPolytope> convexPolytope(const std::vector<Vec3>& vertices,
                                             const std::vector<std::array<int, 3>>& triangles,
                                             double tolerance_m = 1e-6, double min_volume_m3 = 1e-9);

/// A triangular prism: the triangle (a, b, c) and its copy moved by `offset` (the side the solid
/// lies on), e.g. a terrain triangle down to a floor or a surface triangle's slab of thickness t.
std::optional<ConvexPolytope> trianglePrism(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& offset_a,
                                            const Vec3& offset_b, const Vec3& offset_c);

/// Distance from p to the triangle (a, b, c).
double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace msb
