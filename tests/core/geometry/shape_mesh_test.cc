// The truth's tessellation: each primitive's triangles enclose it (outward winding, the
// divergence-theorem volume matches the solid's to the polygon's error), the ground becomes the
// extent's rectangle, and the sampled cloud has the density asked for, all on the surface.
#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/shape_mesh.h"

namespace msb {
namespace {

// Signed volume enclosed by a closed mesh (positive for outward winding).
double enclosedVolume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

// Total area of a mesh.
double area(const TriangleMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  return a;
}

Shape shape(ShapeType type, const Vec3& size, const Vec3& at, double yaw = 0.4) {
  Shape s;
  s.type = type;
  s.size = size;
  s.pose = Pose::Identity();
  s.pose.translation() = at;
  s.pose.linear() = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  return s;
}

TEST(ShapeMesh, EachPrimitiveEnclosesItsVolumeWithOutwardTriangles) {
  const Vec2 lo(-10, -10), hi(10, 10);
  TriangleMesh box, cyl, sph;
  appendShapeMesh(shape(ShapeType::kBox, Vec3(1, 2, 3), Vec3(5, 1, 2)), 0, lo, hi, box);
  EXPECT_NEAR(enclosedVolume(box), 48.0, 1e-9);
  EXPECT_NEAR(area(box), 2 * (4 * 2 + 2 * 6 + 4 * 6) * 1.0, 1e-9);
  appendShapeMesh(shape(ShapeType::kCylinder, Vec3(0.5, 0, 2), Vec3(-3, 0, 2)), 1, lo, hi, cyl);
  const double ngon = 0.5 * kRoundSegments * std::sin(2 * M_PI / kRoundSegments);  // area of the unit 32-gon
  EXPECT_NEAR(enclosedVolume(cyl), ngon * 0.25 * 4, 1e-9);
  appendShapeMesh(shape(ShapeType::kSphere, Vec3(2, 0, 0), Vec3(0, 4, 1)), 2, lo, hi, sph);
  const double ball = 4.0 / 3.0 * M_PI * 8;
  EXPECT_GT(enclosedVolume(sph), 0.97 * ball);
  EXPECT_LT(enclosedVolume(sph), ball);
  for (const TriangleMesh* m : {&box, &cyl, &sph})
    for (const int s : m->shape_of_triangle) EXPECT_EQ(s, m == &box ? 0 : m == &cyl ? 1 : 2);
}

TEST(ShapeMesh, TheGroundIsTheExtentsRectangleFacingUp) {
  Shape ground = shape(ShapeType::kHalfSpace, Vec3::Ones(), Vec3(0, 0, -0.5), 0.7);
  TriangleMesh m;
  appendShapeMesh(ground, 0, Vec2(-4, -1), Vec2(6, 3), m);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_NEAR(area(m), 40.0, 1e-9);
  for (const Vec3& v : m.vertices) EXPECT_NEAR(v.z(), -0.5, 1e-12);
  const auto& t = m.triangles[0];
  EXPECT_GT((m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).z(), 0);
}

TEST(ShapeMesh, TheCloudHasTheDensityAskedForAndLiesOnTheSurface) {
  const Shape b = shape(ShapeType::kBox, Vec3(2, 3, 1), Vec3(1, 1, 1));
  TriangleMesh m;
  appendShapeMesh(b, 0, Vec2::Zero(), Vec2::Ones(), m);
  RngStream rng(1, "test");
  const auto points = sampleSurface(m, 10.0, rng);
  EXPECT_NEAR(double(points.size()), 10.0 * area(m), 0.02 * 10.0 * area(m));
  for (const SurfacePoint& p : points) EXPECT_NEAR(b.signedDistance(p.position), 0.0, 1e-9);
  RngStream again(1, "test");
  EXPECT_EQ(sampleSurface(m, 10.0, again).size(), points.size());
}

}  // namespace
}  // namespace msb
