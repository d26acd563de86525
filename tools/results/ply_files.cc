#include "tools/results/ply_files.h"

#include <bit>
#include <stdexcept>

namespace msb {

namespace {

// Little-endian bytes of a float and an int32, whatever the host.
void putFloat(std::string& s, double v) {
  const uint32_t u = std::bit_cast<uint32_t>(static_cast<float>(v));
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((u >> (8 * i)) & 0xff));
}
void putInt(std::string& s, int v) {
  const uint32_t u = static_cast<uint32_t>(v);
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((u >> (8 * i)) & 0xff));
}

// The header's first lines: format and comments.
std::string headerStart(const std::vector<std::string>& comments) {
  std::string h = "ply\nformat binary_little_endian 1.0\n";
  for (const std::string& c : comments) h += "comment " + c + "\n";
  return h;
}

}  // namespace

std::string binaryPly(const PlyCloud& c) {
  const size_t n = c.xyz.size();
  for (const size_t m : {c.radius.size(), c.kind.size(), c.rgb.size()})
    if (m != 0 && m != n) throw std::invalid_argument("binaryPly: a property's size is not the point count");
  std::string s = headerStart(c.comments) + "element vertex " + std::to_string(n) +
                  "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!c.radius.empty()) s += "property float radius\n";
  if (!c.kind.empty()) s += "property uchar kind\n";
  if (!c.rgb.empty()) s += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  s += "end_header\n";
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) putFloat(s, c.xyz[i][k]);
    if (!c.radius.empty()) putFloat(s, c.radius[i]);
    if (!c.kind.empty()) s.push_back(static_cast<char>(c.kind[i]));
    if (!c.rgb.empty())
      for (const uint8_t v : c.rgb[i]) s.push_back(static_cast<char>(v));
  }
  return s;
}

std::string binaryPlyMesh(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                          const std::vector<std::string>& comments) {
  std::string s = headerStart(comments) + "element vertex " + std::to_string(vertices.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : vertices)
    for (int k = 0; k < 3; ++k) putFloat(s, v[k]);
  for (const auto& t : triangles) {
    s.push_back(3);
    for (const int i : t) putInt(s, i);
  }
  return s;
}

}  // namespace msb
