#include "core/perception/frontend_degradation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace msb {

bool FrontendDegradationConfig::degrades() const {
  return image_noise_sigma > 0.0 || mistrack_share > 0.0 || landmark_jitter_inv_depth > 0.0 || drift_scale != 1.0;
}

void FrontendDegradationConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

namespace {

// The presets' values and their argument: docs/perception.md, "Degradation axes".
struct NamedPreset {
  const char* name;
  FrontendDegradationConfig config;
};

const std::vector<NamedPreset>& presets() {
  static const std::vector<NamedPreset> kPresets = {
      {"clean", {}},
      {"reference", {.landmark_jitter_inv_depth = 0.005}},
      {"real_flight",
       {.image_noise_sigma = 4.0,
        .mistrack_share = 0.03,
        .mistrack_px = 3.0,
        .landmark_jitter_inv_depth = 0.01,
        .drift_scale = 2.0}},
      {"severe",
       {.image_noise_sigma = 8.0,
        .mistrack_share = 0.08,
        .mistrack_px = 4.0,
        .landmark_jitter_inv_depth = 0.02,
        .drift_scale = 4.0}},
  };
  return kPresets;
}

}  // namespace

std::optional<FrontendDegradationConfig> frontendPreset(const std::string& name) {
  for (const auto& p : presets())
    if (name == p.name) return p.config;
  return std::nullopt;
}

std::vector<std::string> frontendPresetNames() {
  std::vector<std::string> names;
  for (const auto& p : presets()) names.emplace_back(p.name);
  return names;
}

ImageNoise::ImageNoise(double sigma, uint64_t seed) : sigma_(sigma), rng_(seed, "frontend_image_noise") {}

namespace {

// The 2^16 standard normal quantiles Φ⁻¹((i + ½) / 2^16), by bisection on erfc: a per-pixel
// normal draw is then one 16-bit table index (four per engine output) — a normal distribution
// to within 2^-16 in probability at a tenth of the cost of a polar-method draw.
const std::vector<float>& normalQuantiles() {
  static const std::vector<float> table = [] {
    constexpr int kSize = 1 << 16;
    std::vector<float> t(kSize);
    for (int i = 0; i < kSize; ++i) {
      const double p = (i + 0.5) / kSize;
      double lo = -10.0, hi = 10.0;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::numbers::sqrt2) < p ? lo : hi) = mid;
      }
      t[size_t(i)] = float(0.5 * (lo + hi));
    }
    return t;
  }();
  return table;
}

}  // namespace

void ImageNoise::apply(CameraFrame& frame) {
  const std::vector<float>& q = normalQuantiles();
  const float sigma = float(sigma_);
  uint64_t draw = 0;
  for (size_t i = 0; i < frame.pixels.size(); ++i) {
    if (i % 4 == 0) draw = rng_.bits();
    const float v = std::nearbyint(float(frame.pixels[i]) + sigma * q[(draw >> (16 * (i % 4))) & 0xffff]);
    frame.pixels[i] = uint8_t(std::clamp(v, 0.0f, 255.0f));
  }
}

MistrackModel::MistrackModel(double share, double px, uint64_t seed)
    : share_(share), px_(px), rng_(seed, "frontend_mistracks") {}

Vec2 MistrackModel::displacement() {
  if (rng_.uniform() >= share_) return Vec2::Zero();
  const double a = rng_.uniform(0.0, 2.0 * std::numbers::pi);
  return px_ * Vec2(std::cos(a), std::sin(a));
}

LandmarkJitter::LandmarkJitter(double sigma_inv_depth, uint64_t seed)
    : sigma_(sigma_inv_depth), rng_(seed, "frontend_landmark_jitter") {}

void LandmarkJitter::apply(SlamPointsFrame& frame) {
  constexpr double kMinInvDepth = 1e-3;  // 1 km: a draw past infinity stays far, in front
  for (SlamPoint& p : frame.points) {
    const Vec3 c = p.T_W_anchor.translation();
    const Vec3 ray = p.p_W - c;
    const double d = ray.norm();
    const double n = rng_.normal();
    if (d <= 0.0) continue;
    const double rho = std::max(1.0 / d + sigma_ * n, kMinInvDepth);
    const double scale = 1.0 / (rho * d);
    p.p_W = c + scale * ray;
    p.depth_m *= scale;
  }
}

}  // namespace msb
