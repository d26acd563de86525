#include "sim/physics/polynomial_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

namespace msb {
namespace {

// Rest-to-rest vertices along x through `xs` (inner vertices fix the position only).
std::vector<PolyVertex> restToRest(const std::vector<double>& xs) {
  std::vector<PolyVertex> v(xs.size());
  for (size_t i = 0; i < xs.size(); ++i) v[i].fixed[0] = Vec4(xs[i], 0, 0, 0);
  for (auto* e : {&v.front(), &v.back()}) e->fixed[1] = e->fixed[2] = Vec4::Zero();
  return v;
}

TEST(PolynomialTrajectory, PassesItsVerticesAndIsContinuousUpToSnap) {
  std::vector<PolyVertex> v = restToRest({0.0, 3.0, 2.0, 7.0});
  v[0].fixed[1] = Vec4(1.0, 0.5, 0, 0.2);  // a moving start, as the tracker's state
  v[0].fixed[3] = Vec4(0.3, 0, 0, 0);
  PolynomialTrajectory p;
  ASSERT_TRUE(p.solve(v, {1.5, 2.0, 2.5}));
  EXPECT_NEAR((p.at(0.0, 1) - Vec4(1.0, 0.5, 0, 0.2)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(p.at(0.0, 3)(0), 0.3, 1e-8);
  EXPECT_NEAR(p.at(1.5, 0)(0), 3.0, 1e-9);
  EXPECT_NEAR(p.at(3.5, 0)(0), 2.0, 1e-9);
  EXPECT_NEAR(p.at(6.0, 0)(0), 7.0, 1e-9);
  EXPECT_NEAR(p.at(6.0, 1).norm() + p.at(6.0, 2).norm(), 0.0, 1e-8);
  // Both sides of an inner vertex agree in derivatives 0…4.
  for (int d = 0; d <= 4; ++d)
    EXPECT_NEAR((p.segmentAt(0, 1.5, d) - p.segmentAt(1, 0.0, d)).norm(), 0.0, 1e-6 * (1 + p.segmentAt(1, 0, d).norm()))
        << "derivative " << d;
}

TEST(PolynomialTrajectory, CostsNoMoreThanTheMinimumJerkQuintic) {
  // 0 → 1 in 1 s at rest: the quintic 10τ³ − 15τ⁴ + 6τ⁵ meets the same constraints with
  // ∫ a² = 120/7; the minimum-acceleration polynomial must cost less.
  PolynomialTrajectory p;
  ASSERT_TRUE(p.solve(restToRest({0.0, 1.0}), {1.0}));
  EXPECT_LT(p.cost(), 120.0 / 7.0);
  EXPECT_GT(p.cost(), 12.0);  // a cubic's ∫ a² = 12 needs a jump in acceleration at the ends
}

TEST(PolynomialTrajectory, TwiceTheTimeCostsAnEighth) {
  // ∫ a² dt of a rest-to-rest trajectory scales as T⁻³.
  PolynomialTrajectory a, b;
  ASSERT_TRUE(a.solve(restToRest({0.0, 4.0, 1.0}), {2.0, 3.0}));
  ASSERT_TRUE(b.solve(restToRest({0.0, 4.0, 1.0}), {4.0, 6.0}));
  EXPECT_NEAR(b.cost() * 8.0, a.cost(), 1e-9 * a.cost());
}

TEST(PolynomialTrajectory, TooFewFixedValuesAreRefused) {
  std::vector<PolyVertex> v(2);  // nothing fixed: the position is free
  PolynomialTrajectory p;
  EXPECT_FALSE(p.solve(v, {1.0}));
}

}  // namespace
}  // namespace msb
