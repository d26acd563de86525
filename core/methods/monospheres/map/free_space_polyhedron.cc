// The only translation unit that includes CGAL (its headers are slow to compile). CGAL comes
// first: Boost.Multiprecision (pulled in by CGAL) calls an unqualified msb(), which a global
// namespace named msb, declared by our headers, would hide.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <limits>

#include "core/methods/monospheres/map/free_space_polyhedron.h"

namespace msb {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Triangle3 = K::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle3>::const_iterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 cg(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

struct FreeSpacePolyhedron::Impl {
  DepthMesh mesh;
  Pose T_C_W = Pose::Identity();
  Delaunay dt;
  std::vector<Triangle3> triangles;  // surface then fan
  AabbTree tree;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  bool valid = false;
};

FreeSpacePolyhedron::FreeSpacePolyhedron(const std::vector<Vec3>& points_W, const Pose& T_W_C, double max_angle_deg)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.T_C_W = T_W_C.inverse();
  m.mesh.camera_W = T_W_C.translation();
  const double min_cos = std::cos(max_angle_deg * M_PI / 180.0);

  // Points in front of the camera, in normalised pinhole coordinates; sorted insertion keeps
  // the triangulation deterministic.
  std::vector<std::pair<K::Point_2, int>> pts;
  for (const auto& p : points_W) {
    const Vec3 c = m.T_C_W * p;
    if (c.norm() < 1e-6 || c.z() < min_cos * c.norm()) continue;
    pts.emplace_back(K::Point_2(c.x() / c.z(), c.y() / c.z()), int(m.mesh.vertices_W.size()));
    m.mesh.vertices_W.push_back(p);
  }
  m.dt.insert(pts.begin(), pts.end());
  if (m.dt.dimension() < 2) return;

  // Surface faces (oriented so the normal faces the camera is not needed: unsigned queries).
  for (auto f = m.dt.finite_faces_begin(); f != m.dt.finite_faces_end(); ++f)
    m.mesh.surface.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  // Boundary: edges of finite faces adjacent to the infinite vertex.
  auto circ = m.dt.incident_faces(m.dt.infinite_vertex()), start = circ;
  do {
    const int i = circ->index(m.dt.infinite_vertex());
    m.mesh.boundary.push_back({circ->vertex(m.dt.ccw(i))->info(), circ->vertex(m.dt.cw(i))->info()});
  } while (++circ != start);

  const auto& V = m.mesh.vertices_W;
  for (const auto& f : m.mesh.surface) m.triangles.emplace_back(cg(V[f[0]]), cg(V[f[1]]), cg(V[f[2]]));
  for (const auto& e : m.mesh.boundary) m.triangles.emplace_back(cg(V[e[0]]), cg(V[e[1]]), cg(m.mesh.camera_W));
  m.tree.rebuild(m.triangles.begin(), m.triangles.end());
  m.tree.accelerate_distance_queries();
  m.lo = m.hi = m.mesh.camera_W;
  for (const auto& v : V) m.lo = m.lo.cwiseMin(v), m.hi = m.hi.cwiseMax(v);
  m.valid = !m.mesh.surface.empty();
}

FreeSpacePolyhedron::~FreeSpacePolyhedron() = default;
FreeSpacePolyhedron::FreeSpacePolyhedron(FreeSpacePolyhedron&&) noexcept = default;
FreeSpacePolyhedron& FreeSpacePolyhedron::operator=(FreeSpacePolyhedron&&) noexcept = default;

bool FreeSpacePolyhedron::valid() const { return impl_->valid; }
const DepthMesh& FreeSpacePolyhedron::mesh() const { return impl_->mesh; }
std::pair<Vec3, Vec3> FreeSpacePolyhedron::bounds() const { return {impl_->lo, impl_->hi}; }

std::optional<double> FreeSpacePolyhedron::surfaceRange(const Vec3& direction_W) const {
  const Impl& m = *impl_;
  if (!m.valid) return std::nullopt;
  const Vec3 d = m.T_C_W.linear() * direction_W;
  if (d.z() <= 1e-9) return std::nullopt;
  const K::Point_2 q(d.x() / d.z(), d.y() / d.z());
  const auto face = m.dt.locate(q);
  if (face == nullptr || m.dt.is_infinite(face)) return std::nullopt;
  // Ray–plane intersection with the lifted triangle (camera frame, ray from the origin).
  const auto& V = m.mesh.vertices_W;
  const Vec3 a = m.T_C_W * V[face->vertex(0)->info()], b = m.T_C_W * V[face->vertex(1)->info()],
             c = m.T_C_W * V[face->vertex(2)->info()];
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 u = d.normalized();
  const double denom = n.dot(u);
  if (std::abs(denom) < 1e-15) return std::nullopt;
  const double t = n.dot(a) / denom;
  if (t <= 0) return std::nullopt;
  return t;
}

bool FreeSpacePolyhedron::contains(const Vec3& p_W) const {
  const Vec3 d = p_W - impl_->mesh.camera_W;
  const double r = d.norm();
  if (r < 1e-12) return impl_->valid;
  const auto range = surfaceRange(d);
  return range && r < *range;
}

double FreeSpacePolyhedron::distance(const Vec3& p_W) const {
  if (!impl_->valid) return std::numeric_limits<double>::infinity();
  return std::sqrt(impl_->tree.squared_distance(cg(p_W)));
}

std::vector<std::array<Vec3, 3>> FreeSpacePolyhedron::triangles() const {
  std::vector<std::array<Vec3, 3>> out;
  for (const auto& t : impl_->triangles) {
    std::array<Vec3, 3> tri;
    for (int i = 0; i < 3; ++i) tri[i] = Vec3(t[i].x(), t[i].y(), t[i].z());
    out.push_back(tri);
  }
  return out;
}

}  // namespace msb
