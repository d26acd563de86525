// Convex polytopes (the pieces of imported meshes): exact signed distance and ray casts against a
// box built as a primitive, refusal of open and concave surfaces, terrain prisms.
#include "core/geometry/convex_polytope.h"

#include <gtest/gtest.h>

#include "core/common/rng.h"
#include "core/geometry/shapes.h"

namespace msb {
namespace {

// A box's 8 corners and 12 triangles, some wound inwards on purpose (convexPolytope turns them).
void boxMesh(const Vec3& half, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& f) {
  for (int k = 0; k < 8; ++k)
    v.emplace_back((k & 1 ? 1 : -1) * half.x(), (k & 2 ? 1 : -1) * half.y(), (k & 4 ? 1 : -1) * half.z());
  f = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
       {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
}

TEST(ConvexPolytope, ABoxMeshMeasuresAsTheBoxPrimitive) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  const Vec3 half(2.0, 1.0, 0.5);
  boxMesh(half, v, f);
  const auto P = convexPolytope(v, f);
  ASSERT_TRUE(P.has_value());
  EXPECT_EQ(P->planes.size(), 6u);  // 12 triangles, 6 faces
  Shape box;
  box.type = ShapeType::kBox;
  box.size = half;
  RngStream rng(3, "convex_box");
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(rng.uniform(-4, 4), rng.uniform(-3, 3), rng.uniform(-2, 2));
    EXPECT_NEAR(P->signedDistance(p), box.signedDistance(p), 1e-9) << p.transpose();
    const Vec3 d = Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
    const auto a = P->raycast(p, d), b = box.raycast(p, d);
    ASSERT_EQ(a.has_value(), b.has_value()) << p.transpose() << " along " << d.transpose();
    if (a) {
      EXPECT_NEAR(*a, *b, 1e-9);
    }
  }
}

TEST(ConvexPolytope, OpenOrConcaveSurfacesAreNotConvexSolids) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  boxMesh(Vec3(1, 1, 1), v, f);
  // Open: one face missing.
  std::vector<std::array<int, 3>> open(f.begin() + 2, f.end());
  EXPECT_FALSE(convexPolytope(v, open).has_value());
  // Concave: one corner pushed into the box (still closed).
  std::vector<Vec3> dented = v;
  dented[7] = Vec3(0.2, 0.2, 0.2);
  EXPECT_FALSE(convexPolytope(dented, f).has_value());
  // Flat: no volume.
  std::vector<Vec3> flat = v;
  for (Vec3& p : flat) p.z() = 0;
  EXPECT_FALSE(convexPolytope(flat, f).has_value());
}

// A terrain triangle down to a floor: inside below the slanted top, outside above it.
TEST(ConvexPolytope, ATerrainPrismHoldsTheSolidUnderItsTriangle) {
  const Vec3 a(0, 0, 1), b(4, 0, 2), c(0, 4, 3);
  const double floor = -1.0;
  const auto P =
      trianglePrism(a, b, c, Vec3(0, 0, floor - a.z()), Vec3(0, 0, floor - b.z()), Vec3(0, 0, floor - c.z()));
  ASSERT_TRUE(P.has_value());
  // The top plane: z = 1 + x/4 + y/2.
  const Vec3 p(1, 1, 1 + 0.25 + 0.5);
  EXPECT_NEAR(P->signedDistance(p + Vec3(0, 0, 0.5)), 0.5 / std::sqrt(1 + 0.0625 + 0.25), 1e-9);
  EXPECT_LT(P->signedDistance(p - Vec3(0, 0, 0.3)), 0.0);
  const auto down = P->raycast(p + Vec3(0, 0, 5), Vec3(0, 0, -1));
  ASSERT_TRUE(down.has_value());
  EXPECT_NEAR(*down, 5.0, 1e-9);
  // Beside the triangle (x + y > 4): outside at every height.
  EXPECT_GT(P->signedDistance(Vec3(3, 3, 0)), 0.0);
}

TEST(ConvexPolytope, PointTriangleDistanceCoversEveryRegion) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(pointTriangleDistance(Vec3(0.2, 0.2, 3), a, b, c), 3.0, 1e-12);         // face
  EXPECT_NEAR(pointTriangleDistance(Vec3(-1, -1, 0), a, b, c), std::sqrt(2), 1e-12);  // vertex a
  EXPECT_NEAR(pointTriangleDistance(Vec3(0.5, -2, 0), a, b, c), 2.0, 1e-12);          // edge ab
  EXPECT_NEAR(pointTriangleDistance(Vec3(1, 1, 0), a, b, c), std::sqrt(0.5), 1e-12);  // edge bc
}

}  // namespace
}  // namespace msb
