// A world's ground truth as solid primitives, queried without MuJoCo: distance to the nearest
// obstacle, inside test, ray casts, and the explorable 2.5 m columns of the exploration box
// (docs/architecture.md §10–11). Built by the world generator from the same description as the MJCF, so both
// agree by construction; tests check them against MuJoCo's mj_ray.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/aabb.h"
#include "core/geometry/shapes.h"

namespace msb {

/// Result of a ray cast against the ground truth.
struct RayHit {
  double distance_m = 0.0;  ///< along the unit direction
  int shape = -1;           ///< index into WorldTruth::shapes()
};

/// Result of a nearest-obstacle query.
struct NearestObstacle {
  double distance_m = 0.0;  ///< signed: negative inside an obstacle
  int shape = -1;           ///< index of the nearest shape
};

/// A 2.5 m column of the exploration box (integer cell indices from the box minimum).
struct Column {
  int ix = 0, iy = 0;
  bool operator<(const Column& o) const { return ix != o.ix ? ix < o.ix : iy < o.iy; }
  bool operator==(const Column& o) const { return ix == o.ix && iy == o.iy; }
};

/// Ground-truth geometry with a 2D grid index over the shapes' footprints.
class WorldTruth {
 public:
  /// Indexes the shapes (cell size of the footprint grid in metres).
  explicit WorldTruth(std::vector<Shape> shapes, double index_cell_m = 4.0);

  /// All shapes (index = shape id).
  const std::vector<Shape>& shapes() const { return shapes_; }
  /// The shape with this name (a MuJoCo geom name), or null if there is none.
  const Shape* shapeNamed(const std::string& name) const;
  /// Nearest obstacle surface (signed distance; exact outside obstacles). Searches up to
  /// `max_range_m`; beyond it returns max_range_m and shape -1.
  NearestObstacle nearest(const Vec3& p, double max_range_m = 50.0) const;
  /// Distance to the nearest obstacle surface (see nearest()).
  double distance(const Vec3& p, double max_range_m = 50.0) const { return nearest(p, max_range_m).distance_m; }
  /// True if p lies inside (or on) any obstacle.
  bool inside(const Vec3& p) const;
  /// First obstacle hit by the ray o + t d (d need not be normalised), within max_range_m.
  std::optional<RayHit> raycast(const Vec3& o, const Vec3& d, double max_range_m = 1e6) const;
  /// The same first hit as raycast() (equal distance and shape), found by walking the footprint
  /// grid along the ray instead of testing every shape: for many short rays (what the camera
  /// saw, core/eval/verified_coverage.h).
  std::optional<RayHit> raycastIndexed(const Vec3& o, const Vec3& d, double max_range_m) const;
  /// Columns of `box` (cells of `cell_m`, from box.min) that are not fully occupied: at least
  /// one sample point on a `sample_m` lattice inside the column lies outside all obstacles.
  std::vector<Column> explorableColumns(const Aabb& box, double cell_m = 2.5, double sample_m = 0.5) const;

 private:
  template <class F>
  void forCell(int cx, int cy, F&& f) const;
  // The first hit of the unit ray o + t d among `shape`, kept if nearer than `best` (ties: the
  // lower index, as raycast()).
  void rayTestShape(int shape, const Vec3& o, const Vec3& d, double max_range_m, std::optional<RayHit>& best) const;

  std::vector<Shape> shapes_;
  std::vector<std::pair<Vec3, Vec3>> bounds_;  // each shape's bounding box (half-spaces: unused)
  std::vector<int> unbounded_;                 // half-spaces, always tested
  double cell_;
  Vec2 origin_ = Vec2::Zero();
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;
};

}  // namespace msb
