// Binary PLY (little-endian) for the field's viewers (Open3D, CloudCompare, MeshLab): point
// clouds with optional radius, kind and colour properties, and triangle meshes; the frame and
// units named in the header's comments (docs/interop.md).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// A point cloud; each optional property vector is empty (left out) or one entry per point.
struct PlyCloud {
  std::vector<Vec3> xyz;                    ///< float x y z
  std::vector<float> radius;                ///< float radius
  std::vector<uint8_t> kind;                ///< uchar kind
  std::vector<std::array<uint8_t, 3>> rgb;  ///< uchar red green blue
  std::vector<std::string> comments;        ///< header comments (frame, units, what kind means)
};

/// The binary PLY text of `cloud`. Throws std::invalid_argument if a property's size is not
/// the point count.
std::string binaryPly(const PlyCloud& cloud);

/// The binary PLY of a triangle mesh: vertex float x y z, face list uchar int vertex_indices.
std::string binaryPlyMesh(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                          const std::vector<std::string>& comments);

}  // namespace msb
