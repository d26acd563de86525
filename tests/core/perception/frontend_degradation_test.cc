#include "core/perception/frontend_degradation.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace msb {
namespace {

// Mean and standard deviation of a sample.
std::pair<double, double> meanStd(const std::vector<double>& x) {
  double m = 0.0, v = 0.0;
  for (double e : x) m += e;
  m /= double(x.size());
  for (double e : x) v += (e - m) * (e - m);
  return {m, std::sqrt(v / double(x.size() - 1))};
}

TEST(FrontendDegradation, DefaultsAndCleanChangeNothingAndPresetsGrowMonotonically) {
  EXPECT_FALSE(FrontendDegradationConfig{}.degrades());
  const auto names = frontendPresetNames();
  ASSERT_EQ(names.front(), "clean");
  EXPECT_FALSE(frontendPreset("clean")->degrades());
  EXPECT_FALSE(frontendPreset("no_such_level").has_value());
  for (size_t i = 1; i < names.size(); ++i) {
    const auto a = *frontendPreset(names[i - 1]), b = *frontendPreset(names[i]);
    EXPECT_TRUE(b.degrades()) << names[i];
    EXPECT_NO_THROW(checkValid(b));
    EXPECT_GE(b.image_noise_sigma, a.image_noise_sigma);
    EXPECT_GE(b.mistrack_share, a.mistrack_share);
    EXPECT_GE(b.landmark_jitter_inv_depth, a.landmark_jitter_inv_depth);
    EXPECT_GE(b.drift_scale, a.drift_scale);
  }
}

TEST(FrontendDegradation, OutOfRangeAxesAreRefusedByName) {
  auto refused = [](FrontendDegradationConfig c, const std::string& key) {
    try {
      checkValid(c);
    } catch (const ConfigError& e) {
      return std::string(e.what()).find(key) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused({.image_noise_sigma = -1.0}, "image_noise_sigma"));
  EXPECT_TRUE(refused({.mistrack_share = 0.9}, "mistrack_share"));
  EXPECT_TRUE(refused({.mistrack_px = 0.0}, "mistrack_px"));
  EXPECT_TRUE(refused({.landmark_jitter_inv_depth = NAN}, "landmark_jitter_inv_depth"));
  EXPECT_TRUE(refused({.drift_scale = 25.0}, "drift_scale"));
}

TEST(ImageNoise, HasTheConfiguredSigmaIsDeterministicAndClamps) {
  CameraFrame mid;
  mid.width = 200, mid.height = 100;
  mid.pixels.assign(20000, 128);
  CameraFrame a = mid, b = mid;
  ImageNoise(6.0, 3).apply(a);
  ImageNoise(6.0, 3).apply(b);
  EXPECT_EQ(a.pixels, b.pixels);  // same seed, same noise
  CameraFrame c = mid;
  ImageNoise(6.0, 4).apply(c);
  EXPECT_NE(a.pixels, c.pixels);
  std::vector<double> d;
  for (uint8_t p : a.pixels) d.push_back(double(p) - 128.0);
  const auto [m, s] = meanStd(d);
  EXPECT_NEAR(m, 0.0, 0.15);
  EXPECT_NEAR(s, 6.0, 0.15);  // rounding adds 1/12 in variance: 6.007
  CameraFrame white = mid;
  white.pixels.assign(20000, 255);
  ImageNoise(6.0, 3).apply(white);
  for (uint8_t p : white.pixels) ASSERT_GT(p, 200);  // clamped at 255, not wrapped round to 0
  EXPECT_GT(std::count(white.pixels.begin(), white.pixels.end(), 255), 9000);
}

TEST(MistrackModel, DisplacesTheConfiguredShareByTheConfiguredSizeInAllDirections) {
  MistrackModel m(0.1, 3.0, 11);
  int displaced = 0;
  Vec2 sum = Vec2::Zero();
  for (int i = 0; i < 20000; ++i) {
    const Vec2 d = m.displacement();
    if (d.norm() == 0.0) continue;
    EXPECT_NEAR(d.norm(), 3.0, 1e-12);
    ++displaced;
    sum += d;
  }
  EXPECT_NEAR(displaced / 20000.0, 0.1, 0.01);
  EXPECT_LT((sum / displaced).norm(), 0.2);  // no preferred direction
  MistrackModel none(0.0, 3.0, 11);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(none.displacement(), Vec2::Zero());
}

TEST(LandmarkJitter, MovesPointsAlongTheirAnchorRayWithTheConfiguredInverseDepthSigma) {
  // Points 5 m from their anchor: the published inverse depth has mean 0.2 and σ 0.01; the
  // points stay on their ray; the same seed gives the same frame.
  SlamPointsFrame f;
  const Vec3 anchor(1.0, 2.0, 3.0);
  const Vec3 dir = Vec3(1.0, 2.0, -0.5).normalized();
  for (int i = 0; i < 20000; ++i) {
    SlamPoint p;
    p.track_id = uint64_t(i);
    p.T_W_anchor = Pose::Identity();
    p.T_W_anchor.translation() = anchor;
    p.p_W = anchor + 5.0 * dir;
    p.depth_m = 5.0;
    f.points.push_back(p);
  }
  SlamPointsFrame a = f, b = f;
  LandmarkJitter(0.01, 5).apply(a);
  LandmarkJitter(0.01, 5).apply(b);
  std::vector<double> rho;
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].p_W, b.points[i].p_W);
    const Vec3 r = a.points[i].p_W - anchor;
    EXPECT_NEAR(r.normalized().dot(dir), 1.0, 1e-12);
    EXPECT_NEAR(a.points[i].depth_m, r.norm(), 1e-9);
    rho.push_back(1.0 / r.norm());
  }
  const auto [m, s] = meanStd(rho);
  EXPECT_NEAR(m, 0.2, 0.0003);
  EXPECT_NEAR(s, 0.01, 0.0003);
}

}  // namespace
}  // namespace msb
