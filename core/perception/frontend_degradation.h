// Front-end degradation: named, physically meaningful axes along which the front end's error can
// be made worse than the faithful reference front end (docs/perception.md, "Degradation axes").
// Off by default. Each axis draws from its own named RNG stream, so turning one on never moves
// another's numbers:
//   - image noise: zero-mean Gaussian noise of σ grey levels on every rendered frame (sensor read
//     and shot noise; low light raises the gain and with it the noise), rounded and clamped;
//   - KLT mis-tracks: a share of the tracks continued into a frame land a few pixels off (the
//     window slid onto the background at an occlusion boundary, or onto a repeated texture); the
//     tracker continues from the wrong position, and its epipolar RANSAC may or may not catch it;
//   - landmark jitter: every published SLAM point moves along its anchor ray by a zero-mean
//     Gaussian step of σ in inverse depth, drawn afresh per published frame (a filter's estimate
//     moving with each update more than msbench's batch refinement moves it);
//   - drift scale: multiplies the VIO drift model's rates and noises (applied by the loop).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/common/rng.h"

namespace msb {

/// The degradation axes; every default leaves the front end as it is.
struct FrontendDegradationConfig {
  double image_noise_sigma = 0.0;          ///< grey levels (of 255), [0, 50]
  double mistrack_share = 0.0;             ///< share of continued tracks displaced per frame, [0, 0.5]
  double mistrack_px = 3.0;                ///< size of a mis-track's displacement, (0, 20] px
  double landmark_jitter_inv_depth = 0.0;  ///< σ of a published point's inverse depth, [0, 0.2] 1/m
  double drift_scale = 1.0;                ///< multiplies the VIO drift rates and noises, [0, 20]

  /// True if any axis differs from the faithful front end.
  bool degrades() const;
  /// The keys, each once with the values it accepts (`preset` is read in tools/config).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("image_noise_sigma", s.image_noise_sigma, Limits::range(0.0, 50.0));
    v.key("mistrack_share", s.mistrack_share, Limits::range(0.0, 0.5));
    v.key("mistrack_px", s.mistrack_px, Limits{0.0, 20.0, true, false});
    v.key("landmark_jitter_inv_depth", s.landmark_jitter_inv_depth, Limits::range(0.0, 0.2));
    v.key("drift_scale", s.drift_scale, Limits::range(0.0, 20.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The named presets, mildest first: clean, reference, real_flight, severe (docs/perception.md).
std::optional<FrontendDegradationConfig> frontendPreset(const std::string& name);
/// The preset names, mildest first.
std::vector<std::string> frontendPresetNames();

/// Gaussian image noise (a table of 2^16 normal quantiles indexed by the stream's bits); owns
/// the "frontend_image_noise" stream.
class ImageNoise {
 public:
  /// σ in grey levels (≥ 0).
  ImageNoise(double sigma, uint64_t seed);
  /// Adds noise to every pixel of the frame (rounded to the nearest level, clamped to [0, 255]).
  void apply(CameraFrame& frame);

 private:
  double sigma_;
  RngStream rng_;
};

/// KLT mis-tracks; owns the "frontend_mistracks" stream.
class MistrackModel {
 public:
  /// A share in [0, 1] of the tracks displaced by `px` pixels in a uniformly random direction.
  MistrackModel(double share, double px, uint64_t seed);
  /// The displacement of one continued track in this frame (zero for most). Called once per
  /// continued track, in track-id order.
  Vec2 displacement();

 private:
  double share_;
  double px_;
  RngStream rng_;
};

/// Landmark estimate jitter; owns the "frontend_landmark_jitter" stream.
class LandmarkJitter {
 public:
  /// σ of the inverse depth along the anchor ray, 1/m (≥ 0).
  LandmarkJitter(double sigma_inv_depth, uint64_t seed);
  /// Moves every point of the frame along its anchor ray (in point order); depth_m follows. A
  /// draw that would put the point behind the anchor (or past 1 km) is clamped there.
  void apply(SlamPointsFrame& frame);

 private:
  double sigma_;
  RngStream rng_;
};

}  // namespace msb
