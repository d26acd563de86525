// Reads a mesh file (any format assimp reads: COLLADA .dae, .obj, .stl, ...) into world-frame
// surfaces, one per node and material, and cuts each node into convex pieces for collision and
// ground truth (MuJoCo collides a mesh as the convex hull of its vertices, so a concave surface
// needs pieces):
//  - a closed convex node is one piece;
//  - a terrain (an open node whose plan covers half the mesh's or more, caves and overhangs
//    allowed) and a closed concave node are cut vertically: each triangle facing up holds the
//    solid below it, down to the node's next surface below at each vertex (a cave's ceiling, a
//    closed part's bottom) or, under a terrain, to a floor 1 m below the whole mesh; a triangle
//    facing down or sideways gets a slab behind it;
//  - any other node (an open sheet: a roof, a fence) is one slab per triangle,
//    `slab_thickness_m` thick, on the side its winding faces away from.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/common/types.h"
#include "core/geometry/convex_polytope.h"

namespace msb {

/// One node's triangles of one material, in the world frame.
struct ImportedSurface {
  std::string node;      ///< the node's name in the file (made unique: name, name_1, ...)
  std::string material;  ///< the material's name
  std::vector<Vec3> vertices;
  std::vector<Vec2> uv;  ///< per vertex, as the file gives them (empty: none)
  std::vector<std::array<int, 3>> triangles;
  std::string texture_file;  ///< the material's diffuse texture as the file names it ("" if none)
  double grey = 0.7;         ///< the material's diffuse colour as grey (used without a texture)
};

/// How a node was cut: whole, vertically (a terrain or a closed concave part), or into slabs.
enum class PieceRule { kConvex, kVertical, kSlabs };

/// A node's collision and truth pieces.
struct ImportedNode {
  std::string node;
  PieceRule rule = PieceRule::kSlabs;
  bool terrain = false;  ///< open and spanning the mesh: the ground (its underside is the floor)
  std::vector<ConvexPolytope> pieces;
};

/// A mesh file read and cut.
struct ImportedMesh {
  std::vector<ImportedSurface> surfaces;
  std::vector<ImportedNode> nodes;
  size_t triangles = 0;
  /// The other files the mesh read, as opened (an OBJ's material library): imported with it.
  std::vector<std::string> side_files;
};

/// Reads `path` with its nodes' transforms and units, scales it by `scale` (the model's mesh
/// scale), places it at T_W_M and cuts every node into pieces. Throws std::runtime_error naming
/// the file when it cannot be read or holds no triangle, or when a coordinate is not finite.
ImportedMesh importMesh(const std::string& path, const Vec3& scale, const Pose& T_W_M, double slab_thickness_m);

/// Name of a piece rule ("convex", "vertical", "slabs").
const char* pieceRuleName(PieceRule r);

}  // namespace msb
