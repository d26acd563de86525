// Solid primitive shapes of a world's ground truth: exact signed distance, inside test and ray
// intersection, no simulator needed. These mirror the MuJoCo collision geoms one to one.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/common/types.h"
#include "core/geometry/convex_polytope.h"

namespace msb {

/// What an obstacle looks like to a sparse visual front end (for map-safety statistics).
enum class ObstacleKind {
  kTextured,     ///< feature-rich surface (walls, bark, rock, foliage)
  kTextureless,  ///< flat colour: cars, burned façades
  kThin,         ///< rods and poles a few centimetres thick
  kGround,       ///< terrain, floor, ceiling
};

/// Name of a kind ("textured", "textureless", "thin", "ground").
const char* obstacleKindName(ObstacleKind kind);

/// Geometric type of a solid primitive.
enum class ShapeType { kBox, kCylinder, kSphere, kHalfSpace, kConvex };

/// A solid primitive in the world frame.
///  - box: half extents `size` along the pose's axes
///  - cylinder: radius size.x, half height size.z, axis = pose z
///  - sphere: radius size.x
///  - half-space: everything below the pose's xy plane (pose z axis is the outward normal)
///  - convex: `polytope`, in the world frame (a piece of an imported mesh); the pose is the
///    identity and `size` the half extents of its bounds
struct Shape {
  ShapeType type = ShapeType::kBox;
  Pose pose = Pose::Identity();  ///< T_W_S
  Vec3 size = Vec3::Ones();      ///< see above
  ObstacleKind kind = ObstacleKind::kTextured;
  std::string name;                                          ///< MuJoCo geom name
  std::string object;                                        ///< the object it belongs to, e.g. "building_3"
  std::shared_ptr<const ConvexPolytope> polytope = nullptr;  ///< convex shapes only

  /// Signed distance from p to the surface (negative inside).
  double signedDistance(const Vec3& p) const;
  /// Distance along the unit ray o + t d to the first surface hit (t >= 0), if any.
  std::optional<double> raycast(const Vec3& o, const Vec3& d) const;
  /// Axis-aligned bounding box (min, max); unbounded shapes give ±1e9.
  std::pair<Vec3, Vec3> bounds() const;
};

}  // namespace msb
