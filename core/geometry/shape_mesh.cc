#include "core/geometry/shape_mesh.h"

#include <cmath>

namespace msb {

namespace {

// Appends a local-frame triangle list (vertices in the shape's frame) moved by `T`.
void appendLocal(const Pose& T, const std::vector<Vec3>& local, const std::vector<std::array<int, 3>>& tris, int shape,
                 TriangleMesh& mesh) {
  const int base = int(mesh.vertices.size());
  for (const Vec3& v : local) mesh.vertices.push_back(T * v);
  for (const auto& t : tris) {
    mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    mesh.shape_of_triangle.push_back(shape);
  }
}

// A box of half extents h: 8 corners, 2 triangles per face.
void boxMesh(const Vec3& h, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& t) {
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  t = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
       {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
}

// A cylinder of radius r and half height hz about z: a ring at each end and their centres.
void cylinderMesh(double r, double hz, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& t) {
  const int n = kRoundSegments;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    v.emplace_back(r * std::cos(a), r * std::sin(a), -hz);
    v.emplace_back(r * std::cos(a), r * std::sin(a), hz);
  }
  v.emplace_back(0, 0, -hz);
  v.emplace_back(0, 0, hz);
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * ((i + 1) % n);
    t.push_back({a, b, b + 1});
    t.push_back({a, b + 1, a + 1});
    t.push_back({2 * n, b, a});
    t.push_back({2 * n + 1, a + 1, b + 1});
  }
}

// A sphere of radius r: kRoundSegments / 2 rings between the poles.
void sphereMesh(double r, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& t) {
  const int n = kRoundSegments, rings = n / 2;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < n; ++i) {
      const double polar = M_PI * j / rings, a = 2 * M_PI * i / n;
      v.emplace_back(r * std::sin(polar) * std::cos(a), r * std::sin(polar) * std::sin(a), r * std::cos(polar));
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i, b = j * n + (i + 1) % n;
      if (j > 0) t.push_back({a, a + n, b});
      if (j < rings - 1) t.push_back({b, a + n, b + n});
    }
}

// A half-space's plane (its local xy plane) over the rectangle [lo, hi]: the rectangle itself
// for a level plane (the ground), else a square of the rectangle's diagonal about the plane's
// point nearest the rectangle's centre.
void planeMesh(const Pose& T, const Vec2& lo, const Vec2& hi, std::vector<Vec3>& v,
               std::vector<std::array<int, 3>>& t) {
  const Vec2 c2 = 0.5 * (lo + hi);
  const Vec3 local_c = T.inverse() * Vec3(c2.x(), c2.y(), 0);
  const bool level = std::abs(T.linear()(2, 2)) > 1 - 1e-9;
  if (level) {
    // Corners in the world, dropped onto the plane (its height at each corner).
    for (const Vec2& xy : {lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())}) {
      Vec3 p = T.inverse() * Vec3(xy.x(), xy.y(), 0);
      p.z() = 0;
      v.push_back(p);
    }
    // Counter-clockwise seen along the normal: flip the order for a downward normal.
    t = T.linear()(2, 2) > 0 ? std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}}
                             : std::vector<std::array<int, 3>>{{0, 2, 1}, {0, 3, 2}};
    return;
  }
  const double h = 0.5 * (hi - lo).norm();
  for (const auto& [x, y] : {std::pair{-h, -h}, {h, -h}, {h, h}, {-h, h}})
    v.emplace_back(local_c.x() + x, local_c.y() + y, 0);
  t = {{0, 1, 2}, {0, 2, 3}};
}

}  // namespace

void appendShapeMesh(const Shape& s, int shape_index, const Vec2& lo, const Vec2& hi, TriangleMesh& mesh) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> t;
  switch (s.type) {
    case ShapeType::kBox:
      boxMesh(s.size, v, t);
      break;
    case ShapeType::kCylinder:
      cylinderMesh(s.size.x(), s.size.z(), v, t);
      break;
    case ShapeType::kSphere:
      sphereMesh(s.size.x(), v, t);
      break;
    case ShapeType::kHalfSpace:
      planeMesh(s.pose, lo, hi, v, t);
      break;
    case ShapeType::kConvex:
      if (s.polytope) appendLocal(Pose::Identity(), s.polytope->vertices, s.polytope->triangles, shape_index, mesh);
      return;
  }
  appendLocal(s.pose, v, t, shape_index, mesh);
}

std::vector<SurfacePoint> sampleSurface(const TriangleMesh& mesh, double per_m2, RngStream& rng) {
  std::vector<SurfacePoint> points;
  for (size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& tri = mesh.triangles[k];
    const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    const double expected = 0.5 * (b - a).cross(c - a).norm() * per_m2;
    int n = int(std::floor(expected));
    if (rng.uniform() < expected - n) ++n;
    for (int i = 0; i < n; ++i) {
      // Uniform on the triangle: fold the unit square's upper half back.
      double u = rng.uniform(), w = rng.uniform();
      if (u + w > 1) u = 1 - u, w = 1 - w;
      points.push_back({a + u * (b - a) + w * (c - a), mesh.shape_of_triangle[k]});
    }
  }
  return points;
}

}  // namespace msb
