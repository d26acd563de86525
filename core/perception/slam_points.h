// SLAM points from feature tracks, like OpenVINS' SLAM features in anchored inverse depth.
//
// Each track keeps its observations (pixel + estimated camera pose). Once the angle between the
// anchor ray (first observation) and a later ray reaches `min_parallax_deg`, the point is
// estimated by Gauss–Newton over all kept observations, in anchored inverse depth: with the
// anchor bearing b0 and an orthonormal pair (e1, e2) ⟂ b0,
//     p_A(a, c, ρ) = (b0 + a e1 + c e2) / ρ           (ρ ≈ inverse depth along b0)
// and residuals r_i = u_i − π(T_Ci_A · p_A) through the shared fisheye model π. The point's
// covariance is σ_px² (JᵀJ)⁻¹ propagated to the world frame. Points with a large reprojection
// error, negative or tiny inverse depth, or a large relative depth uncertainty are withheld.
#pragma once

#include <map>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_check.h"
#include "core/perception/feature_tracker.h"

namespace msb {

/// Triangulation settings.
struct SlamPointsConfig {
  double min_parallax_deg = 4.0;
  double pixel_sigma_px = 1.0;
  double max_reprojection_rms_px = 2.0;
  double max_relative_depth_std = 0.3;   ///< σ_depth / depth
  double max_depth_m = 80.0;
  double min_depth_m = 0.2;
  int max_points = 500;
  int max_observations = 20;             ///< kept per track (anchor + most recent)
  int min_observations = 4;              ///< a point needs this many observations (rejects 2-frame mismatches)
  int max_iterations = 10;

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Per-track observation history and Gauss–Newton refinement.
class SlamPointEstimator {
 public:
  /// Throws ConfigError.
  SlamPointEstimator(const SlamPointsConfig& config, const FisheyeCamera& camera);

  /// Adds the frame's tracks observed from the estimated camera pose T_W_C; returns the SLAM
  /// points of the currently tracked features.
  SlamPointsFrame update(const TrackFrame& tracks, const Pose& T_W_C);

  /// Estimates one point from observations (first = anchor); exposed for tests. Returns false
  /// if the estimate is rejected; `init_depth` > 0 warm-starts.
  bool estimate(const std::vector<std::pair<Vec2, Pose>>& obs, double init_depth, SlamPoint* out) const;

 private:
  struct History {
    std::vector<std::pair<Vec2, Pose>> obs;  // (pixel, T_W_C); obs[0] is the anchor
    int64_t anchor_tick = 0;
    double last_depth = 0.0;
  };

  SlamPointsConfig config_;
  FisheyeCamera camera_;
  std::map<uint64_t, History> histories_;
};

}  // namespace msb
