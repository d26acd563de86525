// An oracle feature source: what an ideal sparse front end would track. Landmarks are sampled
// once on the surfaces of the world's ground-truth shapes (seeded); each frame, the landmarks
// in front of the true camera, within range, inside the field of view and not occluded (a ray
// cast against the ground truth) are projected through the shared fisheye model with Gaussian
// pixel noise. A landmark keeps its track id while it stays visible. New tracks are spread like
// the KLT tracker's (at least min_distance_px apart, up to max_tracks). Textureless surfaces
// and thin rods carry no landmarks by default, as no corner detector finds features there.
//
// Clearly not the benchmark's front end: it never looks at the image. It exists for fast loop
// tests (with the null renderer) and as a front-end ablation (`perception.source: oracle`):
// how much of a method's result the monocular front end costs.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/common/rng.h"
#include "core/geometry/world_truth.h"
#include "core/perception/feature_tracker.h"

namespace msb {

/// Oracle feature source settings.
struct OracleFeatureConfig {
  int max_tracks = 400;                ///< tracks per frame, as the KLT tracker
  double min_distance_px = 20.0;       ///< between new features and existing ones
  double pixel_noise_px = 0.5;         ///< 1σ Gaussian noise per observation and axis
  double landmark_spacing_m = 1.0;     ///< one landmark per spacing² of surface
  double max_range_m = 60.0;           ///< landmarks farther from the camera are not seen
  double ground_margin_m = 20.0;       ///< ground planes carry landmarks this far beyond the objects
  int border_px = 8;                   ///< no features this close to the image or FoV border
  bool textureless_landmarks = false;  ///< landmarks on textureless surfaces too (a perfect front end)
  bool thin_landmarks = false;         ///< landmarks on thin rods too

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("max_tracks", s.max_tracks, Limits::range(1, 100000));
    v.key("min_distance_px", s.min_distance_px, Limits::nonNegative());
    v.key("pixel_noise_px", s.pixel_noise_px, Limits::nonNegative());
    v.key("landmark_spacing_m", s.landmark_spacing_m, Limits::range(0.1, 100.0));
    v.key("max_range_m", s.max_range_m, Limits::positive());
    v.key("ground_margin_m", s.ground_margin_m, Limits::nonNegative());
    v.key("border_px", s.border_px, Limits::range(0, 1000));
    v.key("textureless_landmarks", s.textureless_landmarks);
    v.key("thin_landmarks", s.thin_landmarks);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Feature tracks from the ground truth (see file comment).
class OracleFeatureSource final : public FeatureSource {
 public:
  /// Samples the landmarks (stream `oracle_landmarks`); pixel noise uses `oracle_pixel_noise`.
  /// `truth` must outlive the source. Throws ConfigError.
  OracleFeatureSource(const OracleFeatureConfig& config, const FisheyeCamera& camera, const WorldTruth& truth,
                      uint64_t seed);

  /// Tracks seen from the frame's ground-truth camera pose (frame.T_W_C); pixels are not read.
  TrackFrame process(const CameraFrame& frame) override;

  /// Number of landmarks sampled on the world's surfaces.
  size_t landmarkCount() const { return landmarks_.size(); }

 private:
  struct Landmark {
    Vec3 p_W;       // on a surface
    Vec3 normal_W;  // outward surface normal
  };
  void sampleLandmarks(RngStream& rng);
  // The steps of sampleLandmarks(): a surface's landmark count, one landmark, each shape type.
  int landmarkCount(double area, RngStream& rng) const;
  void addLandmark(const Shape& s, const Vec3& p_S, const Vec3& n_S);
  void sampleBox(const Shape& s, RngStream& rng);
  void sampleCylinder(const Shape& s, RngStream& rng);
  void sampleSphere(const Shape& s, RngStream& rng);
  void sampleConvex(const Shape& s, RngStream& rng);
  void samplePlane(const Shape& s, const Vec3& lo, const Vec3& hi, RngStream& rng);
  bool visible(const Landmark& l, const Pose& T_W_C, Vec2* pixel) const;

  OracleFeatureConfig config_;
  FisheyeCamera camera_;
  const WorldTruth& truth_;
  RngStream noise_;
  std::vector<Landmark> landmarks_;  // shuffled once, so index order is spatially random
  std::vector<uint64_t> track_of_;   // landmark → current track id (0 = not tracked)
  std::vector<size_t> tracked_;      // landmarks tracked in the previous frame
  std::vector<int> age_;             // per landmark
  uint64_t next_id_ = 1;
};

}  // namespace msb
