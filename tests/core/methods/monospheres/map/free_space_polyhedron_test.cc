#include "core/methods/monospheres/map/free_space_polyhedron.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/common/rng.h"

namespace msb {
namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Ray (o, d) crosses triangle (Möller–Trumbore), strictly in front of o.
bool crosses(const Vec3& o, const Vec3& d, const std::array<Vec3, 3>& t) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], h = d.cross(e2);
  const double a = e1.dot(h);
  if (std::abs(a) < 1e-14) return false;
  const double f = 1.0 / a;
  const Vec3 s = o - t[0];
  const double u = f * s.dot(h);
  if (u < 0 || u > 1) return false;
  const Vec3 q = s.cross(e1);
  const double v = f * d.dot(q);
  if (v < 0 || u + v > 1) return false;
  return f * e2.dot(q) > 1e-12;
}

TEST(FreeSpacePolyhedron, KnownPyramid) {
  // Four points on a 10 x 10 m square 10 m ahead: P_f is a square pyramid.
  const Pose T_W_C = Pose::Identity();  // optical frame = world frame
  const std::vector<Vec3> pts = {{-5, -5, 10}, {5, -5, 10}, {5, 5, 10}, {-5, 5, 10}};
  const FreeSpacePolyhedron P(pts, T_W_C);
  ASSERT_TRUE(P.valid());
  EXPECT_EQ(P.mesh().surface.size(), 2u);
  EXPECT_EQ(P.mesh().boundary.size(), 4u);
  EXPECT_TRUE(P.contains({0, 0, 5}));
  EXPECT_TRUE(P.contains({4, 4, 9.5}));
  EXPECT_FALSE(P.contains({0, 0, 11}));
  EXPECT_FALSE(P.contains({6, 0, 10}));
  EXPECT_FALSE(P.contains({0, 0, -1}));
  EXPECT_NEAR(*P.surfaceRange(Vec3(0, 0, 1)), 10.0, 1e-12);
  EXPECT_FALSE(P.surfaceRange(Vec3(1, 0, 0)));
  // Nearest boundary of (0, 0, 5): a side face of the pyramid, 5/sqrt(5) away.
  EXPECT_NEAR(P.distance({0, 0, 5}), 5.0 / std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(P.distance({0, 0, 12}), 2.0, 1e-9);
}

TEST(FreeSpacePolyhedron, InsideAndDistanceMatchBruteForceOnRandomMeshes) {
  RngStream rng(21, "polyhedron");
  for (int mesh_i = 0; mesh_i < 8; ++mesh_i) {
    const Pose T_W_C = poseFromXyzYaw(Vec3(rng.uniform(-5, 5), rng.uniform(-5, 5), 2), rng.uniform(-3, 3)) *
                       Pose(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitY()) * Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
    std::vector<Vec3> pts;
    for (int i = 0; i < 80; ++i) {
      const double th = rng.uniform(0, 70) * M_PI / 180, ph = rng.uniform(-M_PI, M_PI), r = rng.uniform(2, 20);
      pts.push_back(T_W_C * Vec3(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)));
    }
    const FreeSpacePolyhedron P(pts, T_W_C);
    ASSERT_TRUE(P.valid());
    const auto tris = P.triangles();
    int mismatches = 0, inside = 0;
    for (int q = 0; q < 1500; ++q) {
      // Half the queries anywhere around, half inside the camera's cone (near the surface too).
      Vec3 p = T_W_C * Vec3(rng.uniform(-25, 25), rng.uniform(-25, 25), rng.uniform(-3, 25));
      if (q % 2) {
        const double th = rng.uniform(0, 75) * M_PI / 180, ph = rng.uniform(-M_PI, M_PI), r = rng.uniform(0.5, 22);
        p = T_W_C * Vec3(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th));
      }
      // Brute force inside: parity of crossings along a random ray of the closed surface.
      const Vec3 d = Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
      int n = 0;
      for (const auto& t : tris) n += crosses(p, d, t);
      const bool brute_inside = n % 2 == 1;
      mismatches += brute_inside != P.contains(p);
      inside += brute_inside;
      // Brute force distance: nearest point over all faces.
      double best = 1e18;
      for (const auto& t : tris) best = std::min(best, (closestOnTriangle(p, t[0], t[1], t[2]) - p).norm());
      ASSERT_NEAR(P.distance(p), best, 1e-9);
    }
    EXPECT_LE(mismatches, 2) << "mesh " << mesh_i;  // grazing rays may double-count an edge
    EXPECT_GT(inside, 150);
  }
}

TEST(FreeSpacePolyhedron, TooFewOrDegeneratePointsGiveAnInvalidPolyhedron) {
  EXPECT_FALSE(FreeSpacePolyhedron({{0, 0, 5}, {1, 0, 5}}, Pose::Identity()).valid());
  EXPECT_FALSE(FreeSpacePolyhedron({{0, 0, 5}, {1, 0, 5}, {2, 0, 5}}, Pose::Identity()).valid());
  // Points behind the camera are ignored.
  EXPECT_FALSE(FreeSpacePolyhedron({{0, 0, -5}, {1, 0, -5}, {0, 1, -5}}, Pose::Identity()).valid());
  EXPECT_FALSE(FreeSpacePolyhedron({}, Pose::Identity()).contains({0, 0, 1}));
}

}  // namespace
}  // namespace msb
