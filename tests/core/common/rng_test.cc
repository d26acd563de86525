#include "core/common/rng.h"

#include <gtest/gtest.h>

#include <cmath>

namespace msb {
namespace {

TEST(RngStream, SameSeedAndNameGiveTheSameSequence) {
  RngStream a(42, "imu"), b(42, "imu");
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.uniform(), b.uniform());
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.normal(), b.normal());
}

TEST(RngStream, StreamsAreIndependentByNameAndSeed) {
  RngStream a(42, "imu"), b(42, "vio_drift"), c(43, "imu");
  EXPECT_NE(a.engineSeed(), b.engineSeed());
  EXPECT_NE(a.engineSeed(), c.engineSeed());
  EXPECT_NE(a.uniform(), b.uniform());
}

TEST(RngStream, KnownFirstValuesPinThePortableTransforms) {
  // The transforms are ours, so these values must not change across platforms or releases.
  // (std::mt19937_64 itself is fully specified by the C++ standard.)
  RngStream r(1, "test");
  EXPECT_EQ(r.engineSeed(), 16012389208725400575ULL);
  EXPECT_DOUBLE_EQ(r.uniform(), 0.41641875739701839);
  EXPECT_DOUBLE_EQ(r.normal(), -1.1959128319676449);
}

TEST(RngStream, UniformAndNormalHaveTheRightMoments) {
  RngStream r(7, "moments");
  const int n = 200000;
  double su = 0, su2 = 0, sn = 0, sn2 = 0, sn4 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u, su2 += u * u;
    const double g = r.normal();
    sn += g, sn2 += g * g, sn4 += g * g * g * g;
  }
  EXPECT_NEAR(su / n, 0.5, 0.005);
  EXPECT_NEAR(su2 / n - 0.25, 1.0 / 12.0, 0.002);
  EXPECT_NEAR(sn / n, 0.0, 0.01);
  EXPECT_NEAR(sn2 / n, 1.0, 0.01);
  EXPECT_NEAR(sn4 / n, 3.0, 0.08);
}

TEST(RngStream, UniformIntIsInRangeAndCoversIt) {
  RngStream r(3, "ints");
  int hist[7] = {};
  for (int i = 0; i < 70000; ++i) {
    const auto k = r.uniformInt(7);
    ASSERT_LT(k, 7u);
    ++hist[k];
  }
  for (int h : hist) EXPECT_NEAR(h, 10000, 500);
}

TEST(Fnv1a, KnownVector) {
  // FNV-1a 64 of "a" is 0xaf63dc4c8601ec8c.
  EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cULL);
}

}  // namespace
}  // namespace msb
