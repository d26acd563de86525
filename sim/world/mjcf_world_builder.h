// Emits a static MJCF world and its ground-truth shapes from solid primitives, one call per
// solid. Every solid has one collision geom (a MuJoCo primitive: faithful collisions) whose
// shape is recorded for the ground truth. Its look is one of:
//  - textured: a visual mesh of the same solid with texture coordinates in metres / tile size,
//    so every surface shows the pattern at its real scale (MuJoCo maps 2D textures onto boxes
//    only along x/y, and cube textures once per face whatever its size); the collision geom is
//    then hidden (geom group 4) and the mesh (group 1) never collides;
//  - flat: the collision geom itself rendered in a uniform grey (textureless surfaces);
//  - cube: the collision geom rendered with a cube-mapped texture (spheres, e.g. canopies).
// A flat look may name a merge group (Look::mergedInto): the collision geom is then hidden and
// its surface joins one visual mesh per (group, grey level), so an object built from many flat
// parts (a vehicle) costs the renderer a few draws instead of one per part.
#pragma once

#include <array>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/geometry/shapes.h"

namespace msb {

/// Geom groups of generated worlds.
namespace geom_groups {
inline constexpr int kRendered = 0;       ///< collision geoms drawn as they are
inline constexpr int kVisualMesh = 1;     ///< textured visual meshes (no collision)
inline constexpr int kCollisionOnly = 4;  ///< collision geoms hidden from the camera
inline constexpr int kSky = 5;            ///< sky planes (drawn with the renderer's `sky` switch)
}  // namespace geom_groups

/// A world geom with this conaffinity bit is ground (an imported terrain's pieces): before
/// take-off, resting on it is no collision, as on a ground plane. The vehicle's contype (2)
/// does not meet it, so contacts still come from the world's contype 1.
inline constexpr int kGroundConaffinityBit = 4;

/// How a solid looks.
struct Look {
  enum Type { kTextured, kFlat, kCube, kHidden } type = kFlat;
  std::string texture;      ///< pattern name (textured, cube)
  double grey = 0.5;        ///< intensity in [0, 1] (flat)
  std::string top_texture;  ///< textured boxes: a different pattern on the top face (roofs)
  std::string merge_group;  ///< flat boxes and cylinders: drawn as part of this group's mesh

  static Look textured(std::string t, std::string top = "") {
    return {kTextured, std::move(t), 0.5, std::move(top), ""};
  }
  static Look flat(double g) { return {kFlat, "", g, "", ""}; }
  static Look cube(std::string t) { return {kCube, std::move(t), 0.5, "", ""}; }
  /// Collision only; the look comes from separate visual slabs (e.g. cave rock skins).
  static Look hidden() { return {kHidden, "", 0.5, "", ""}; }
  /// This look, drawn as part of the merge group's mesh (flat looks only).
  Look mergedInto(std::string group) const {
    Look l = *this;
    l.merge_group = std::move(group);
    return l;
  }
};

/// Accumulates solids; produces MJCF text and shapes.
class MjcfWorldBuilder {
 public:
  /// `texture_tile_m` gives the tile size in metres of each pattern.
  explicit MjcfWorldBuilder(std::string model_name) : model_name_(std::move(model_name)) {}

  /// A box with half extents `half` at pose T (world frame).
  void addBox(const std::string& name, const std::string& object, const Pose& T, const Vec3& half, ObstacleKind kind,
              const Look& look);
  /// A cylinder (radius, half height) along T's z axis.
  void addCylinder(const std::string& name, const std::string& object, const Pose& T, double radius, double half_height,
                   ObstacleKind kind, const Look& look);
  /// A sphere.
  void addSphere(const std::string& name, const std::string& object, const Vec3& centre, double radius,
                 ObstacleKind kind, const Look& look);
  /// A visual-only textured box (no collision, no ground-truth shape), e.g. the skin of a
  /// larger collision solid whose hidden faces need not be drawn.
  void addVisualSlab(const std::string& name, const Pose& T, const Vec3& half, const std::string& texture);
  /// A convex piece (world frame) as a hidden collision mesh geom (MuJoCo collides its convex
  /// hull, which is the piece) and a ground-truth shape; `ground` marks it as ground to rest on.
  void addConvex(const std::string& name, const std::string& object, ConvexPolytope piece, ObstacleKind kind,
                 bool ground);
  /// A visual-only mesh (no collision, no shape) with texture coordinates, drawn with `texture`:
  /// a pattern name, or an image added with addImageTexture.
  void addTexturedMesh(const std::string& name, const std::vector<Vec3>& v, const std::vector<Vec2>& uv,
                       const std::vector<std::array<int, 3>>& faces, const std::string& texture);
  /// A visual-only mesh in one flat grey.
  void addFlatMesh(const std::string& name, const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& faces,
                   double grey);
  /// Declares an image texture (written as textures/<name>.png by the cache, not generated).
  void addImageTexture(const std::string& name) { image_textures_.insert(name); }
  /// An outdoor sky: five inward-facing planes (a lid and four walls) well beyond the ground,
  /// flat and self-lit (no collision, no ground-truth shape), and a world-fixed sun. Worlds
  /// without it (caves) have neither.
  void setOutdoorSky(const Vec2& ground_size_m);
  /// The sun's direction (default: msbench's, (0.62, 0.47, -0.63)).
  void setSunDirection(const Vec3& dir) { sun_direction_ = dir; }
  /// The ground: plane z = 0 of the given extent with a texture repeating every tile.
  void setGround(const Vec2& size_m, const std::string& texture);

  /// The MJCF document (textures referenced as textures/<name>.png).
  std::string mjcf() const;
  /// The ground-truth shapes, in insertion order.
  const std::vector<Shape>& shapes() const { return shapes_; }
  /// Texture patterns referenced.
  const std::set<std::string>& texturesUsed() const { return textures_; }
  /// Number of collision and visual-only geoms.
  int collisionGeoms() const { return int(shapes_.size()); }
  int visualGeoms() const { return visual_geoms_ + int(merged_.size()); }

 private:
  std::string material(const Look& look);
  void addMesh(const std::string& name, const std::vector<Vec3>& v, const std::vector<Vec2>& uv,
               const std::vector<std::array<int, 3>>& faces, const std::string& material);
  std::string collisionGeom(const Shape& s, const Look& look, const std::string& material);
  // Appends a solid's triangles to its merge group's mesh (flat looks with a merge group).
  void mergeSurface(const Look& look, const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& faces);
  // A flat look drawn as part of a merged mesh.
  static bool merged(const Look& look) { return look.type == Look::kFlat && !look.merge_group.empty(); }
  void addBoxMesh(const std::string& name, const Pose& T, const Vec3& half, const std::string& texture,
                  const std::string& top_texture = "");

  std::string model_name_;
  std::vector<Shape> shapes_;
  std::set<std::string> textures_, cube_textures_, image_textures_;
  std::map<int, std::string> flat_materials_;  // grey level (0..255) -> material
  std::ostringstream assets_, bodies_;
  struct MergedMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> faces;
  };
  std::map<std::pair<std::string, std::string>, MergedMesh> merged_;  // (group, material) → mesh
  int visual_geoms_ = 0;
  bool outdoor_ = false;
  Vec3 sun_direction_ = Vec3(0.62, 0.47, -0.63);
};

}  // namespace msb
