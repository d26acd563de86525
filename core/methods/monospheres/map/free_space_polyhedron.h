// The free-space polyhedron P_f of one map update (MonoSpheres §III-A, docs/architecture.md §7 steps 2 and 4).
//
// The SLAM points in front of the camera are triangulated in 2D and lifted back to 3D with the
// same connectivity: the "depth mesh". P_f is the depth mesh closed by a fan of triangles from
// its boundary to the camera centre. The 2D triangulation (CGAL Delaunay) is done in normalised
// pinhole coordinates (x/z, y/z) rather than fisheye pixels: a central projection maps each
// planar 3D triangle onto exactly its 2D triangle, so P_f is exactly star-shaped from the camera
// (no fold-overs where fisheye-space edges would curve), and the inside test is a 2D point
// location plus one ray–plane intersection. Points more than `max_angle_deg` off the optical
// axis are left out (the projection degenerates at 90°).
//
// Distances are exact: the closest point on any face (depth surface or fan), through a CGAL
// AABB tree.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// Vertices and faces of P_f.
struct DepthMesh {
  Vec3 camera_W = Vec3::Zero();              ///< camera centre (the fan apex)
  std::vector<Vec3> vertices_W;              ///< lifted points (world frame)
  std::vector<std::array<int, 3>> surface;   ///< depth-surface triangles (vertex indices)
  std::vector<std::array<int, 2>> boundary;  ///< convex-hull edges of the 2D triangulation
};

/// P_f with inside and distance queries. Immutable after construction.
class FreeSpacePolyhedron {
 public:
  /// Triangulates the points (world frame) seen from camera pose T_W_C (optical frame: z forward).
  /// Points behind the camera or beyond `max_angle_deg` are ignored. Valid if ≥ 3 points remain
  /// in general position (see valid()).
  FreeSpacePolyhedron(const std::vector<Vec3>& points_W, const Pose& T_W_C, double max_angle_deg = 80.0);
  ~FreeSpacePolyhedron();
  FreeSpacePolyhedron(FreeSpacePolyhedron&&) noexcept;
  FreeSpacePolyhedron& operator=(FreeSpacePolyhedron&&) noexcept;

  /// True if the mesh has at least one surface triangle.
  bool valid() const;
  /// The mesh (surface + boundary for the fan).
  const DepthMesh& mesh() const;
  /// True if p lies inside P_f (between the camera and the depth surface).
  bool contains(const Vec3& p_W) const;
  /// Exact distance from p to the boundary of P_f (depth surface or fan).
  double distance(const Vec3& p_W) const;
  /// Range of the depth surface along a camera ray (world direction); none outside the cone
  /// spanned by the triangulated points.
  std::optional<double> surfaceRange(const Vec3& direction_W) const;
  /// Axis-aligned bounds (min, max) of P_f.
  std::pair<Vec3, Vec3> bounds() const;
  /// All closed-surface triangles (surface then fan), as vertex triples.
  std::vector<std::array<Vec3, 3>> triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace msb
