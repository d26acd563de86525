// A world's truth as triangles and as a point cloud sampled on them (msbench world export,
// docs/interop.md): every solid primitive tessellated in the world frame — boxes exactly,
// cylinders and spheres as polygons of a fixed count, convex pieces by their own triangles,
// half-spaces as a square of their plane over a given extent.
#pragma once

#include <array>
#include <vector>

#include "core/common/rng.h"
#include "core/geometry/shapes.h"

namespace msb {

/// Triangles (counter-clockwise seen from outside) over shared vertices, with the index of the
/// shape each triangle came from.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> shape_of_triangle;  ///< index into the shapes the mesh was made from
};

/// Segments around a cylinder or a sphere's equator (a sphere has half as many rings).
inline constexpr int kRoundSegments = 32;

/// Appends `shape` (index `shape_index`) to `mesh`; a half-space becomes its plane over the xy
/// rectangle [lo, hi]: that rectangle for a level plane (the ground), else a square of the
/// rectangle's diagonal about the plane's point nearest the rectangle's centre.
void appendShapeMesh(const Shape& shape, int shape_index, const Vec2& lo, const Vec2& hi, TriangleMesh& mesh);

/// One point on a mesh's surface and the shape it lies on.
struct SurfacePoint {
  Vec3 position;
  int shape = -1;
};

/// Points drawn uniformly by area on `mesh` at `per_m2` points per square metre (each
/// triangle gets floor(area · per_m2) points plus one more with the remainder's probability),
/// from `rng`: the same mesh, density and stream give the same points.
std::vector<SurfacePoint> sampleSurface(const TriangleMesh& mesh, double per_m2, RngStream& rng);

}  // namespace msb
