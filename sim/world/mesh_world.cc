#include "sim/world/mesh_world.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <set>

#include "core/common/config_check.h"
#include "core/common/png.h"
#include "core/common/rng.h"
#include "sim/world/procedural_textures.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// Where an image a mesh names lies, relative to the checkout: beside the mesh file (Gazebo's
// rule), by its file name when the mesh gives an absolute path or a file:// URI. A name that
// leads out of the checkout ('..' past its root) is never read or copied: it stays inside, by its
// file name beside the mesh.
std::string imagePath(const std::string& mesh_file, std::string image) {
  if (image.rfind("file://", 0) == 0) image = image.substr(7);
  const fs::path p(image);
  const fs::path dir = fs::path(mesh_file).parent_path();
  const fs::path rel = (dir / (p.is_absolute() ? p.filename() : p)).lexically_normal();
  if (rel.empty() || *rel.begin() == "..") return (dir / p.filename()).lexically_normal().string();
  return rel.string();
}

// The image as grey PNG bytes, its longer side at most max_px; empty if it cannot be decoded.
std::string greyPng(const fs::path& file, int max_px) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(file.c_str(), &w, &h, &n, 1);
  if (!data) return "";
  cv::Mat grey(h, w, CV_8UC1, data);
  cv::Mat out;
  const double f = double(max_px) / std::max(w, h);
  if (f < 1.0)
    cv::resize(grey, out, cv::Size(), f, f, cv::INTER_AREA);
  else
    out = grey.clone();
  stbi_image_free(data);
  return encodePng(viewOf(out));
}

// A surface's texture coordinates in tiles of `tile_m` world metres, each triangle projected on
// the plane its normal faces most (its vertices repeated per triangle).
void planarTexcoords(const ImportedSurface& s, double tile_m, std::vector<Vec3>& v, std::vector<Vec2>& uv,
                     std::vector<std::array<int, 3>>& f) {
  for (const auto& t : s.triangles) {
    const Vec3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a).cwiseAbs();
    const int axis = n.x() >= n.y() && n.x() >= n.z() ? 0 : n.y() >= n.z() ? 1 : 2;
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    const int base = int(v.size());
    for (const Vec3* p : {&a, &b, &c}) {
      v.push_back(*p);
      uv.emplace_back((*p)[i] / tile_m, (*p)[j] / tile_m);
    }
    f.push_back({base, base + 1, base + 2});
  }
}

// The imported mesh of spec entry i, read from the source directory.
ImportedMesh readMesh(const WorldSpec& spec, size_t i) {
  const MeshSpec& m = spec.meshes[i];
  const std::string key = "meshes[" + std::to_string(i) + "].file";
  const fs::path path = fs::path(spec.source_dir) / m.file;
  if (fs::exists(fs::symlink_status(path)) && !fs::is_regular_file(path))
    throw ConfigError(key, path.string() +
                               ": is there but not a regular file (a FIFO, device, directory or a link "
                               "to nothing)");
  if (!fs::is_regular_file(path)) {
    const std::string from = spec.source ? spec.source->repository + " at " + spec.source->commit : "its source";
    throw ConfigError(key, m.file + " is not in " + spec.source_dir + ": clone " + from +
                               " and run `msbench world import " + spec.name + " --from CLONE`");
  }
  try {
    return importMesh(path.string(), m.mirrored ? Vec3(m.scale.x(), -m.scale.y(), m.scale.z()) : m.scale,
                      poseFromXyzYaw(m.at, m.yaw_deg * kDeg), m.slab_thickness_m);
  } catch (const std::runtime_error& e) {
    throw ConfigError(key, e.what());
  }
}

// The visual meshes of one imported mesh's surfaces.
void buildSurfaces(const WorldSpec& spec, size_t i, const ImportedMesh& mesh, const std::string& id,
                   MjcfWorldBuilder& b, std::map<std::string, std::string>& images, MeshBuildReport& report) {
  const MeshSpec& m = spec.meshes[i];
  std::map<std::string, std::string> texture_of;  // image path → texture name ("" if absent)
  for (size_t k = 0; k < mesh.surfaces.size(); ++k) {
    const ImportedSurface& s = mesh.surfaces[k];
    const std::string name = id + "_" + s.node + "_vis" + std::to_string(k);
    if (s.texture_file.empty()) {
      b.addFlatMesh(name, s.vertices, s.triangles, s.grey);
      continue;
    }
    const std::string rel = imagePath(m.file, s.texture_file);
    if (!texture_of.count(rel)) {
      const std::string png = greyPng(fs::path(spec.source_dir) / rel, m.max_texture_px);
      char tex[32] = "";
      if (!png.empty())
        std::snprintf(tex, sizeof(tex), "img_%016llx", (unsigned long long)fnv1a64(png.data(), png.size()));
      texture_of[rel] = tex;
      if (!png.empty()) images[tex] = png, b.addImageTexture(tex), report.images.push_back(rel);
    }
    const std::string& tex = texture_of[rel];
    if (!tex.empty()) {  // the image through the file's texture coordinates (none: flat grey)
      if (s.uv.size() != s.vertices.size()) {
        b.addFlatMesh(name, s.vertices, s.triangles, s.grey);
        continue;
      }
      std::vector<Vec2> uv;
      for (const Vec2& t : s.uv) uv.emplace_back(t.x(), 1.0 - t.y());  // image rows run downwards
      b.addTexturedMesh(name, s.vertices, uv, s.triangles, tex);
      continue;
    }
    // The image is absent: the spec's stand-in pattern in world metres, or an error.
    if (m.missing_texture.empty())
      throw ConfigError("meshes[" + std::to_string(i) + "].file",
                        m.file + ": material '" + s.material + "' names the image " + rel +
                            ", which is not in the imported source (a partial clone?); import a full checkout or "
                            "set meshes[" +
                            std::to_string(i) + "].missing_texture");
    const std::string& pattern = m.missing_texture;
    if (std::find(report.stand_ins.begin(), report.stand_ins.end(), rel) == report.stand_ins.end())
      report.stand_ins.push_back(rel);
    std::vector<Vec3> v;
    std::vector<Vec2> uv;
    std::vector<std::array<int, 3>> f;
    planarTexcoords(s, textureTileMeters(pattern), v, uv, f);
    b.addTexturedMesh(name, v, uv, f, pattern);
  }
}

}  // namespace

std::vector<MeshBuildReport> buildMeshes(const WorldSpec& spec, MjcfWorldBuilder& b,
                                         std::map<std::string, std::string>& images) {
  std::vector<MeshBuildReport> out;
  for (size_t i = 0; i < spec.meshes.size(); ++i) {
    const MeshSpec& m = spec.meshes[i];
    const ImportedMesh mesh = readMesh(spec, i);
    MeshBuildReport report;
    report.file = m.file;
    report.triangles = mesh.triangles;
    const std::string id = "mesh" + std::to_string(i);
    const ObstacleKind kind = m.kind == "textureless" ? ObstacleKind::kTextureless : ObstacleKind::kTextured;
    // Collision and truth: each node's pieces, named after the node.
    for (const ImportedNode& node : mesh.nodes) {
      const bool terrain = node.terrain;
      const std::string object = id + "_" + node.node;
      for (size_t k = 0; k < node.pieces.size(); ++k)
        b.addConvex(object + "_" + std::to_string(k), object, node.pieces[k], terrain ? ObstacleKind::kGround : kind,
                    terrain);
      report.nodes.emplace_back(node.node, std::string(terrain ? "terrain, " : "") + pieceRuleName(node.rule) + ", " +
                                               std::to_string(node.pieces.size()) +
                                               (node.pieces.size() == 1 ? " piece" : " pieces"));
    }
    buildSurfaces(spec, i, mesh, id, b, images, report);
    out.push_back(std::move(report));
  }
  return out;
}

std::vector<std::string> meshSourceFiles(const WorldSpec& spec, const std::string& checkout,
                                         std::vector<std::string>& missing) {
  std::vector<std::string> files;
  std::set<std::string> seen;
  WorldSpec from = spec;
  from.source_dir = checkout;
  for (size_t i = 0; i < spec.meshes.size(); ++i) {
    if (seen.insert(spec.meshes[i].file).second) files.push_back(spec.meshes[i].file);
    const ImportedMesh mesh = readMesh(from, i);
    // The files the mesh itself read (an OBJ's material library), relative to the checkout.
    for (const std::string& f : mesh.side_files) {
      const std::string rel = fs::path(f).lexically_normal().lexically_relative(fs::path(checkout).lexically_normal());
      if (!rel.empty() && seen.insert(rel).second) files.push_back(rel);
    }
    for (const ImportedSurface& s : mesh.surfaces) {
      if (s.texture_file.empty()) continue;
      const std::string rel = imagePath(spec.meshes[i].file, s.texture_file);
      if (!seen.insert(rel).second) continue;
      if (fs::is_regular_file(fs::path(checkout) / rel))
        files.push_back(rel);
      else
        missing.push_back(rel);
    }
  }
  return files;
}

}  // namespace msb
