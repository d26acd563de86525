// Sparse feature tracking on fisheye images, like the OpenVINS KLT front end: FAST corners
// detected on a grid (threshold 15, ≥ 20 px apart), pyramidal Lucas–Kanade from frame to frame
// with a forward–backward consistency check, histogram equalisation, up to 400 tracks with
// stable ids and ages. Works in fisheye pixel space; bearings come from the shared camera model.
// Single-threaded OpenCV calls only (the caller sets cv::setNumThreads(0) for determinism).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_check.h"
#include "core/common/messages.h"

namespace msb {

/// One tracked feature in the current frame.
struct Track {
  uint64_t id = 0;      ///< stable over the track's life
  Vec2 pixel;           ///< fisheye pixel (continuous, centres at integers)
  int age = 0;          ///< frames since first detection (0 = new in this frame)
};

/// Tracks in one frame.
struct TrackFrame {
  int64_t tick = 0;
  double t_s = 0.0;
  std::vector<Track> tracks;   ///< sorted by id
  int new_tracks = 0;          ///< detected in this frame
  int lost_tracks = 0;         ///< tracks of the previous frame not continued
};

/// Tracker settings (OpenVINS-like defaults, docs/architecture.md §6).
struct FeatureTrackerConfig {
  int max_tracks = 400;              ///< total tracks
  int grid_cols = 5;                 ///< detection grid
  int grid_rows = 3;
  int fast_threshold = 15;           ///< FAST intensity threshold
  double min_distance_px = 20.0;     ///< between features
  int klt_window_px = 21;            ///< LK window side
  int klt_pyramid_levels = 3;        ///< pyramid levels above the base
  int klt_max_iterations = 30;
  double fb_max_error_px = 1.0;      ///< forward–backward consistency threshold
  int border_px = 8;                 ///< no features this close to the image or FoV border
  bool equalize_histogram = true;

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Interface of feature sources (image tracker; later, an oracle source for fast tests).
class FeatureSource {
 public:
  virtual ~FeatureSource() = default;
  /// Tracks for a new frame.
  virtual TrackFrame process(const CameraFrame& frame) = 0;
};

/// Grid-FAST + pyramidal KLT tracker.
class KltFeatureTracker final : public FeatureSource {
 public:
  /// Builds the tracker; the camera gives the valid-pixel mask. Throws ConfigError.
  KltFeatureTracker(const FeatureTrackerConfig& config, const FisheyeCamera& camera);

  TrackFrame process(const CameraFrame& frame) override;

 private:
  void detect(const cv::Mat& img, std::vector<Track>& tracks, int* added);

  FeatureTrackerConfig config_;
  FisheyeCamera camera_;
  cv::Mat valid_mask_;               // pixels inside the FoV, away from its border
  std::vector<cv::Mat> prev_pyramid_;
  std::vector<Track> prev_tracks_;
  uint64_t next_id_ = 1;
};

}  // namespace msb
