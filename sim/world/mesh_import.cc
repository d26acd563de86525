#include "sim/world/mesh_import.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <sys/stat.h>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace msb {

namespace {

// assimp's file access, recorded: every file a mesh reads (the mesh, an OBJ's material library)
// is listed, so an import copies all of them; a path that is there but no regular file (a FIFO,
// a device, a directory) is never opened — it would block or never end — and is named instead.
class RecordingIOSystem : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    struct stat st {};
    if (::stat(file, &st) == 0 && !S_ISREG(st.st_mode)) {
      refused.push_back(file);
      return nullptr;
    }
    Assimp::IOStream* stream = DefaultIOSystem::Open(file, mode);
    if (stream) opened.push_back(file);
    return stream;
  }
  /// Asked by stat, never by opening (DefaultIOSystem's fopen blocks on a FIFO).
  bool Exists(const char* file) const override {
    struct stat st {};
    if (::stat(file, &st) != 0) return false;
    if (!S_ISREG(st.st_mode)) refused.push_back(file);
    return S_ISREG(st.st_mode);
  }
  std::vector<std::string> opened;
  mutable std::vector<std::string> refused;
};

// A file's node name as a MuJoCo-safe word (letters, digits, '_'), unique within the file.
std::string uniqueNodeName(const std::string& raw, std::set<std::string>& taken) {
  std::string s;
  for (char c : raw) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (s.empty()) s = "node";
  std::string name = s;
  for (int k = 1; taken.count(name); ++k) name = s + "_" + std::to_string(k);
  taken.insert(name);
  return name;
}

// The material's diffuse texture path and colour.
void readMaterial(const aiMaterial* m, ImportedSurface& s) {
  aiString name;
  if (m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) s.material = name.C_Str();
  aiString tex;
  if (m->GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS) s.texture_file = tex.C_Str();
  aiColor3D c(0.7f, 0.7f, 0.7f);
  m->Get(AI_MATKEY_COLOR_DIFFUSE, c);
  s.grey = std::clamp(0.299 * c.r + 0.587 * c.g + 0.114 * c.b, 0.0, 1.0);
}

// Every node's meshes, transformed into the world frame, as surfaces.
struct SceneReader {
  const aiScene* scene;
  Vec3 scale;
  Pose T_W_M;
  std::set<std::string> taken;
  std::vector<ImportedSurface> surfaces;

  void read(const aiNode* node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 T = parent * node->mTransformation;
    const std::string name = node->mNumMeshes ? uniqueNodeName(node->mName.C_Str(), taken) : "";
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh* mesh = scene->mMeshes[node->mMeshes[k]];
      if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      ImportedSurface s;
      s.node = name;
      readMaterial(scene->mMaterials[mesh->mMaterialIndex], s);
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        const aiVector3D p = T * mesh->mVertices[v];
        s.vertices.push_back(T_W_M * Vec3(scale.x() * p.x, scale.y() * p.y, scale.z() * p.z));
        if (mesh->HasTextureCoords(0)) s.uv.emplace_back(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y);
      }
      // A mirroring scale (a held-out world's mirror) turns the faces inside out: wound back.
      const bool flip = scale.x() * scale.y() * scale.z() < 0;
      for (unsigned f = 0; f < mesh->mNumFaces; ++f)
        if (mesh->mFaces[f].mNumIndices == 3) {
          const unsigned* i = mesh->mFaces[f].mIndices;
          s.triangles.push_back({int(i[0]), int(flip ? i[2] : i[1]), int(flip ? i[1] : i[2])});
        }
      if (!s.triangles.empty()) surfaces.push_back(std::move(s));
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) read(node->mChildren[c], T);
  }
};

// A node's surfaces as one vertex list, vertices at the same position (to 10 µm) merged, so
// edges across material and texture seams are shared.
void weld(const std::vector<const ImportedSurface*>& parts, std::vector<Vec3>& v,
          std::vector<std::array<int, 3>>& tris) {
  std::map<std::array<long long, 3>, int> index;
  for (const ImportedSurface* s : parts) {
    std::vector<int> map(s->vertices.size());
    for (size_t i = 0; i < s->vertices.size(); ++i) {
      const Vec3& p = s->vertices[i];
      const std::array<long long, 3> key = {std::llround(p.x() * 1e5), std::llround(p.y() * 1e5),
                                            std::llround(p.z() * 1e5)};
      auto [it, fresh] = index.try_emplace(key, int(v.size()));
      if (fresh) v.push_back(p);
      map[i] = it->second;
    }
    for (const auto& t : s->triangles) tris.push_back({map[t[0]], map[t[1]], map[t[2]]});
  }
}

// Whether every edge of the surface is shared by exactly two triangles.
bool isClosed(const std::vector<std::array<int, 3>>& tris) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) ++edges[std::minmax(t[k], t[(k + 1) % 3])];
  for (const auto& [e, n] : edges)
    if (n != 2) return false;
  return true;
}

// The height of the node's surface next below p (the highest triangle under p's vertical
// through its projection, at least 0.1 mm lower), if any.
std::optional<double> nextSurfaceBelow(const Vec3& p, const std::vector<Vec3>& v,
                                       const std::vector<std::array<int, 3>>& tris) {
  std::optional<double> best;
  for (const auto& t : tris) {
    const Vec3 &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
    const double d = (b.y() - c.y()) * (a.x() - c.x()) + (c.x() - b.x()) * (a.y() - c.y());
    if (std::abs(d) < 1e-12) continue;  // a vertical triangle: no height over its projection
    const double l1 = ((b.y() - c.y()) * (p.x() - c.x()) + (c.x() - b.x()) * (p.y() - c.y())) / d;
    const double l2 = ((c.y() - a.y()) * (p.x() - c.x()) + (a.x() - c.x()) * (p.y() - c.y())) / d;
    const double l3 = 1.0 - l1 - l2;
    if (l1 < -1e-9 || l2 < -1e-9 || l3 < -1e-9) continue;
    const double z = l1 * a.z() + l2 * b.z() + l3 * c.z();
    if (z < p.z() - 1e-4 && (!best || z > *best)) best = z;
  }
  return best;
}

// Cuts one node into pieces. A closed convex node is one piece. A terrain (open and spanning
// most of the mesh) or a closed concave node is cut vertically: each triangle facing up
// (n_z ≥ 0.05) holds the solid below it down to the node's next surface below (per vertex: a
// cave's ceiling, a closed part's bottom) or, for a terrain, to the floor; triangles facing
// down or sideways get a slab behind them. Any other node (an open sheet) is slabs.
ImportedNode cutNode(const std::string& name, const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris,
                     double floor_z, double slab_m, bool spans_mesh) {
  ImportedNode out;
  out.node = name;
  Vec3 lo = v[0], hi = v[0];
  for (const Vec3& p : v) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (auto whole = convexPolytope(v, tris, 1e-4 * (hi - lo).norm() + 1e-6)) {
    out.rule = PieceRule::kConvex;
    out.pieces.push_back(std::move(*whole));
    return out;
  }
  const bool closed = isClosed(tris);
  out.terrain = !closed && spans_mesh;
  out.rule = closed || out.terrain ? PieceRule::kVertical : PieceRule::kSlabs;
  for (const auto& t : tris) {
    const Vec3 &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;  // degenerate: no area to stand on
    std::optional<ConvexPolytope> piece;
    if (out.rule == PieceRule::kVertical && n.normalized().z() >= 0.05) {
      // Down to the next surface below each vertex; a terrain's open underside is the floor.
      std::array<double, 3> bottom{};
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const auto below = nextSurfaceBelow(v[t[k]], v, tris);
        ok = ok && (below || !closed);
        bottom[k] = below ? *below : floor_z;
      }
      if (ok)
        piece = trianglePrism(a, b, c, Vec3(0, 0, bottom[0] - a.z()), Vec3(0, 0, bottom[1] - b.z()),
                              Vec3(0, 0, bottom[2] - c.z()));
    }
    if (!piece) {
      const Vec3 off = -slab_m * n.normalized();
      piece = trianglePrism(a, b, c, off, off, off);
    }
    if (piece) out.pieces.push_back(std::move(*piece));
  }
  return out;
}

}  // namespace

const char* pieceRuleName(PieceRule r) {
  switch (r) {
    case PieceRule::kConvex:
      return "convex";
    case PieceRule::kVertical:
      return "vertical";
    case PieceRule::kSlabs:
      return "slabs";
  }
  return "?";
}

ImportedMesh importMesh(const std::string& path, const Vec3& scale, const Pose& T_W_M, double slab_thickness_m) {
  // The mesh itself a regular file before assimp looks at it (it would block on a FIFO).
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw std::runtime_error(path + ": not a regular file (a FIFO, device or directory)");
  Assimp::Importer importer;
  auto* io = new RecordingIOSystem;  // owned by the importer
  importer.SetIOHandler(io);
  // The file's own up axis is kept (Gazebo reads COLLADA as z-up); units and node transforms apply.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!io->refused.empty())
    throw std::runtime_error(path + ": reads " + io->refused.front() +
                             ", which is not a regular file (a FIFO, device or directory)");
  if (!scene || !scene->mRootNode)
    throw std::runtime_error(path + ": cannot be read as a mesh: " + importer.GetErrorString());
  SceneReader reader{scene, scale, T_W_M, {}, {}};
  reader.read(scene->mRootNode, aiMatrix4x4());
  ImportedMesh out;
  out.surfaces = std::move(reader.surfaces);
  for (const std::string& f : io->opened)
    if (f != path && std::find(out.side_files.begin(), out.side_files.end(), f) == out.side_files.end())
      out.side_files.push_back(f);
  // Every coordinate finite; the floor 1 m below the lowest vertex.
  double floor_z = std::numeric_limits<double>::infinity();
  for (const ImportedSurface& s : out.surfaces) {
    out.triangles += s.triangles.size();
    for (const Vec3& p : s.vertices) {
      if (!p.allFinite()) throw std::runtime_error(path + ": node '" + s.node + "' has a non-finite vertex");
      floor_z = std::min(floor_z, p.z() - 1.0);
    }
  }
  if (out.triangles == 0) throw std::runtime_error(path + ": holds no triangle");
  // Each node's surfaces welded and cut, in the file's node order.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const ImportedSurface*>> by_node;
  for (const ImportedSurface& s : out.surfaces) {
    if (!by_node.count(s.node)) order.push_back(s.node);
    by_node[s.node].push_back(&s);
  }
  // A node spans the mesh when its plan covers half of the whole mesh's plan (a terrain).
  Vec2 mesh_lo = Vec2::Constant(1e18), mesh_hi = -mesh_lo;
  for (const ImportedSurface& s : out.surfaces)
    for (const Vec3& p : s.vertices) mesh_lo = mesh_lo.cwiseMin(p.head<2>()), mesh_hi = mesh_hi.cwiseMax(p.head<2>());
  const double mesh_area = (mesh_hi - mesh_lo).prod();
  for (const std::string& name : order) {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> tris;
    weld(by_node[name], v, tris);
    Vec2 lo = Vec2::Constant(1e18), hi = -lo;
    for (const Vec3& p : v) lo = lo.cwiseMin(p.head<2>()), hi = hi.cwiseMax(p.head<2>());
    const bool spans = (hi - lo).prod() >= 0.5 * mesh_area;
    out.nodes.push_back(cutNode(name, v, tris, floor_z, slab_thickness_m, spans));
  }
  return out;
}

}  // namespace msb
