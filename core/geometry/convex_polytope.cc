#include "core/geometry/convex_polytope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace msb {

double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Ericson, Real-Time Collision Detection §5.1.5: the closest point by Voronoi regions.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

double ConvexPolytope::signedDistance(const Vec3& p) const {
  // Inside: the nearest face plane is the nearest surface point (convexity).
  double worst = -std::numeric_limits<double>::infinity();
  for (const auto& [n, d] : planes) worst = std::max(worst, n.dot(p) - d);
  if (worst <= 0.0) return worst;
  // Outside: the nearest surface triangle.
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : triangles)
    best = std::min(best, pointTriangleDistance(p, vertices[t[0]], vertices[t[1]], vertices[t[2]]));
  return best;
}

std::optional<double> ConvexPolytope::raycast(const Vec3& o, const Vec3& d) const {
  // Cyrus–Beck: the ray's parameter interval inside every face's half-space.
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (const auto& [n, off] : planes) {
    const double num = off - n.dot(o), den = n.dot(d);
    if (std::abs(den) < 1e-15) {
      if (num < 0.0) return std::nullopt;  // parallel and outside this face
      continue;
    }
    const double t = num / den;
    if (den < 0.0)
      t0 = std::max(t0, t);  // entering
    else
      t1 = std::min(t1, t);  // leaving
    if (t0 > t1) return std::nullopt;
  }
  return t0;
}

std::pair<Vec3, Vec3> ConvexPolytope::bounds() const {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return {lo, hi};
}

std::optional<ConvexPolytope> convexPolytope(const std::vector<Vec3>& vertices,
                                             const std::vector<std::array<int, 3>>& triangles, double tolerance_m,
                                             double min_volume_m3) {
  ConvexPolytope P;
  P.vertices = vertices;
  for (const auto& t : triangles)
    if (((vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]])).norm() > 2e-12)
      P.triangles.push_back(t);
  if (P.triangles.size() < 4) return std::nullopt;
  // Closed: every undirected edge belongs to exactly two triangles.
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : P.triangles)
    for (int k = 0; k < 3; ++k) ++edges[std::minmax(t[k], t[(k + 1) % 3])];
  for (const auto& [e, n] : edges)
    if (n != 2) return std::nullopt;
  // Outward winding (away from the centroid of the used vertices), then convexity.
  Vec3 centroid = Vec3::Zero();
  int used = 0;
  std::vector<bool> is_used(vertices.size(), false);
  for (const auto& t : P.triangles)
    for (int i : t) is_used[i] = true;
  for (size_t i = 0; i < vertices.size(); ++i)
    if (is_used[i]) centroid += vertices[i], ++used;
  centroid /= used;
  double volume = 0.0;
  for (auto& t : P.triangles) {
    const Vec3 &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
    Vec3 n = (b - a).cross(c - a).normalized();
    if (n.dot(a - centroid) < 0.0) std::swap(t[1], t[2]), n = -n;
    const double d = n.dot(a);
    for (size_t i = 0; i < vertices.size(); ++i)
      if (is_used[i] && n.dot(vertices[i]) - d > tolerance_m) return std::nullopt;
    volume += (vertices[t[0]] - centroid).dot((vertices[t[1]] - centroid).cross(vertices[t[2]] - centroid)) / 6.0;
    // Coplanar triangles share a plane.
    const bool known = std::any_of(P.planes.begin(), P.planes.end(), [&](const auto& pl) {
      return pl.first.dot(n) > 1.0 - 1e-9 && std::abs(pl.second - d) <= tolerance_m;
    });
    if (!known) P.planes.emplace_back(n, d);
  }
  if (volume < min_volume_m3) return std::nullopt;
  // Only the used vertices remain (the triangles' indices renumbered).
  std::vector<int> index(vertices.size(), -1);
  std::vector<Vec3> kept;
  for (size_t i = 0; i < vertices.size(); ++i)
    if (is_used[i]) index[i] = int(kept.size()), kept.push_back(vertices[i]);
  for (auto& t : P.triangles)
    for (int& i : t) i = index[i];
  P.vertices = std::move(kept);
  return P;
}

std::optional<ConvexPolytope> trianglePrism(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& offset_a,
                                            const Vec3& offset_b, const Vec3& offset_c) {
  const std::vector<Vec3> v = {a, b, c, a + offset_a, b + offset_b, c + offset_c};
  // Two caps and three side quads (two triangles each); convexPolytope orients them.
  const std::vector<std::array<int, 3>> f = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4}, {0, 4, 1},
                                             {1, 4, 5}, {1, 5, 2}, {2, 5, 3}, {2, 3, 0}};
  // A side quad of a slanted prism may bend slightly; a millimetre of tolerance keeps it.
  return convexPolytope(v, f, 1e-3, 1e-9);
}

}  // namespace msb
