// SLAM points from feature tracks, as OpenVINS makes its SLAM features in the reference stack
// (docs/perception.md, "SLAM points"; rpng/open_vins VioManager and FeatureInitializer):
//
//  - a sliding window of clones: every camera frame is a clone; the window spans the duration of
//    `max_clones` clones at the reference's tracking rate (11 at 21 Hz ≈ 0.52 s), i.e.
//    round(max_clones · frame_rate / reference_rate_hz) clones at msbench's frame rate;
//  - which tracks: a track observed in every clone of the window (a "max track": it reaches the
//    clone being marginalised) is a SLAM candidate; no SLAM features before `dt_slam_delay_s`
//    after the first frame; at most `max_slam_in_update` new ones per frame (longest-lived
//    tracks first, then lower id) and `max_slam` in the state. A candidate not taken, or refused,
//    starts a new window (OpenVINS uses it for an MSCKF update and drops its measurements);
//  - triangulation from the window's observations only, anchored at the newest: linear
//    triangulation (refused if the 3×3 system's condition number exceeds `max_cond_number` or
//    the depth along the anchor's optical axis is outside [min_dist_m, max_dist_m]), then
//    Gauss–Newton in anchored inverse depth, then refused if the depth is outside the range, if
//    |p| / (largest transverse baseline of the window's clones) exceeds `max_baseline`, or if the
//    reprojection RMS exceeds `max_reprojection_rms_px` (a stand-in for the EKF's χ² gate);
//  - in the state a feature is refined with every new observation (Gauss–Newton over its
//    initialisation window and its most recent observations, a batch stand-in for the EKF
//    update, which never forgets the window's information) for as long
//    as it is tracked; a lost track is marginalised (dropped). A failed refinement is the χ²
//    gate's rejection: that observation is dropped and the failure counted for the feature's
//    life, never reset; the second failure marginalises the feature (OpenVINS' update_fail_count).
//
// Parameterisation: with the anchor bearing b0 and an orthonormal pair (e1, e2) ⟂ b0,
//     p_A(a, c, ρ) = (b0 + a e1 + c e2) / ρ           (ρ ≈ inverse depth along b0)
// and residuals r_i = u_i − π(T_Ci_A · p_A) through the shared fisheye model π. The point's
// covariance is σ_px² (JᵀJ)⁻¹ propagated to the world frame.
#pragma once

#include <map>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/perception/feature_tracker.h"

namespace msb {

/// SLAM-point settings: OpenVINS' values in the reference configuration (docs/perception.md).
struct SlamPointsConfig {
  int max_clones = 11;                   ///< clones in the sliding window (reference: 11)
  double reference_rate_hz = 21.0;       ///< tracking rate those clones were taken at (reference: 21 Hz)
  double dt_slam_delay_s = 1.0;          ///< no SLAM features this long after the first frame
  int max_slam_in_update = 25;           ///< new SLAM features per frame at most
  int max_slam = 500;                    ///< SLAM features in the state at most
  double min_dist_m = 0.1;               ///< feature initialiser: depth along the anchor axis ...
  double max_dist_m = 60.0;              ///< ... within [min_dist_m, max_dist_m]
  double max_baseline = 40.0;            ///< |p| / max transverse baseline at most
  double max_cond_number = 10000.0;      ///< of the linear triangulation's 3×3 system
  double pixel_sigma_px = 1.0;           ///< measurement noise (covariances)
  double max_reprojection_rms_px = 2.0;  ///< χ² stand-in at initialisation and refinement
  int max_observations = 20;             ///< kept per SLAM feature for refinement (its window + most recent)
  int max_iterations = 10;               ///< Gauss–Newton iterations

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("max_clones", s.max_clones, Limits::range(2, 100));
    v.key("reference_rate_hz", s.reference_rate_hz, Limits::positive());
    v.key("dt_slam_delay_s", s.dt_slam_delay_s, Limits::nonNegative());
    v.key("max_slam_in_update", s.max_slam_in_update, Limits::range(1, 100000));
    v.key("max_slam", s.max_slam, Limits::range(1, 100000));
    v.key("min_dist_m", s.min_dist_m, Limits::positive());
    v.key("max_dist_m", s.max_dist_m, Limits::positive());
    v.key("max_baseline", s.max_baseline, Limits::positive());
    v.key("max_cond_number", s.max_cond_number, Limits::positive());
    v.key("pixel_sigma_px", s.pixel_sigma_px, Limits::positive());
    v.key("max_reprojection_rms_px", s.max_reprojection_rms_px, Limits::positive());
    v.key("max_observations", s.max_observations, Limits::range(2, 1000));
    v.key("max_iterations", s.max_iterations, Limits::range(1, 100));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The SLAM features of a sliding-window estimator, from tracks and estimated camera poses.
class SlamPointEstimator {
 public:
  /// `frame_rate_hz`: the rate update() is called at (sizes the clone window). Throws ConfigError.
  SlamPointEstimator(const SlamPointsConfig& config, const FisheyeCamera& camera, double frame_rate_hz);

  /// Adds the frame's tracks observed from the estimated camera pose T_W_C; returns the SLAM
  /// features in the state that are tracked in this frame (sorted by track id).
  SlamPointsFrame update(const TrackFrame& tracks, const Pose& T_W_C);

  /// Clones in the window at this frame rate.
  int windowClones() const { return window_clones_; }

  /// The feature initialiser on a window's observations (first = anchor): linear triangulation
  /// with its checks, Gauss–Newton, then the depth, baseline and reprojection checks. Returns
  /// false if refused. Exposed for tests.
  bool initialise(const std::vector<std::pair<Vec2, Pose>>& obs, SlamPoint* out) const;

  /// Gauss–Newton from `init_depth` (> 0) along the anchor ray; fills `out` and returns false
  /// if it diverges or the reprojection RMS is too large. Exposed for tests.
  bool refine(const std::vector<std::pair<Vec2, Pose>>& obs, double init_depth, SlamPoint* out) const;

 private:
  struct Observation {
    Vec2 pixel;
    Pose T_W_C;
    int64_t tick = 0;
  };
  struct TrackState {
    std::vector<Observation> window;    // observations since the track (re)started, newest last
    int64_t first_tick = 0;             // the track's first observation (its age, for the order)
    bool slam = false;                  // in the state
    std::vector<Observation> slam_obs;  // anchor first, then the most recent
    double depth = 0.0;                 // along the anchor ray
    int fail_count = 0;                 // failed updates in the feature's life (never reset)
    SlamPoint last;                     // the latest estimate
  };

  bool refineFeature(TrackState& s, SlamPoint* out) const;
  // The steps of update(): this frame's observations; the features in the state refined (returns
  // how many stay); the max tracks initialised as new features.
  void addObservations(const TrackFrame& tracks, const Pose& T_W_C);
  int refineInState(std::map<uint64_t, SlamPoint>& points);
  void initialiseMaxTracks(double t_s, int in_state, std::map<uint64_t, SlamPoint>& points);

  SlamPointsConfig config_;
  FisheyeCamera camera_;
  int window_clones_;
  bool started_ = false;
  double start_t_s_ = 0.0;
  std::map<uint64_t, TrackState> tracks_;
};

}  // namespace msb
