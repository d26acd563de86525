// Sparse feature tracking on fisheye images, like the OpenVINS KLT front end: FAST corners
// detected on a grid (threshold 15, ≥ 20 px apart), pyramidal Lucas–Kanade from frame to frame,
// forward only as TrackKLT (a forward–backward check is an option, off), histogram equalisation,
// up to 400 tracks with stable ids and ages. Works in fisheye pixel space; bearings come from the shared camera model.
// Geometric outlier rejection as OpenVINS' front end does it: the tracked pairs' bearings within
// ransac_max_angle_deg of the axis give a fundamental matrix by RANSAC (7-point, OpenCV, as
// TrackKLT) on normalised coordinates; every tracked pair whose angular epipolar error exceeds
// the threshold (ransac_threshold_px at the image centre) is dropped.
// Single-threaded OpenCV calls only (the caller sets cv::setNumThreads(0) for determinism).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/perception/frontend_degradation.h"

namespace msb {

/// One tracked feature in the current frame.
struct Track {
  uint64_t id = 0;  ///< stable over the track's life
  Vec2 pixel;       ///< fisheye pixel (continuous, centres at integers)
  int age = 0;      ///< frames since first detection (0 = new in this frame)
};

/// Tracks in one frame.
struct TrackFrame {
  int64_t tick = 0;
  double t_s = 0.0;
  std::vector<Track> tracks;  ///< sorted by id
  int new_tracks = 0;         ///< detected in this frame
  int lost_tracks = 0;        ///< tracks of the previous frame not continued
  int ransac_rejected = 0;    ///< tracked pairs dropped as epipolar outliers
  int ransac_tested = 0;      ///< tracked pairs the epipolar test was applied to
};

/// Tracks continued from the previous frame (age ≥ 1): what tracking loss counts (a frame whose
/// features are all new has lost track, however many corners were detected).
int trackedFromPrevious(const TrackFrame& f);

/// Clears the status of every point whose final position lies where cv::calcOpticalFlowPyrLK's
/// level-0 error pass would have found its window out of range (window corner floor(p − half
/// window) below −window or at/after the image size, or not a number). Called after a KLT run
/// without the error output, it leaves exactly the status the run with the error output gives.
void dropOutsideWindowRange(const std::vector<cv::Point2f>& points, cv::Size window, cv::Size image,
                            std::vector<uchar>& status);

/// The FAST corners (OpenCV's, with non-maximum suppression) that cv::FAST finds in `img(roi)`
/// and that lie where `mask` (CV_8UC1, the image's size) is non-zero, in image coordinates:
/// the same corners, responses and positions, in another order. Only the rows and columns
/// within reach of a non-zero mask pixel are scanned (FAST's circle of 3 px and the
/// suppression's neighbour), in bands of rows, each a window of its own.
std::vector<cv::KeyPoint> fastWhereFree(const cv::Mat& img, cv::Rect roi, const cv::Mat& mask, int threshold);

/// Tracker settings (OpenVINS-like defaults, docs/architecture.md §6).
struct FeatureTrackerConfig {
  int max_tracks = 400;  ///< total tracks
  int grid_cols = 5;     ///< detection grid
  int grid_rows = 3;
  int fast_threshold = 15;        ///< FAST intensity threshold
  double min_distance_px = 20.0;  ///< between features
  int klt_window_px = 15;         ///< LK window side (OpenVINS TrackKLT: 15×15)
  int klt_pyramid_levels = 5;     ///< pyramid levels above the base (OpenVINS TrackKLT: pyr_levels 5)
  int klt_max_iterations = 30;
  bool forward_backward_check = false;  ///< track back and drop inconsistent tracks (TrackKLT does not: off)
  double fb_max_error_px = 1.0;         ///< forward–backward consistency threshold (with the check)
  int border_px = 8;                    ///< no features this close to the image or FoV border
  bool equalize_histogram = true;
  bool ransac = true;                  ///< epipolar outlier rejection of tracked pairs
  double ransac_threshold_px = 1.0;    ///< epipolar error threshold (pixels at the image centre)
  double ransac_max_angle_deg = 80.0;  ///< bearings used for the estimate (normalised coords)
  int ransac_min_pairs = 10;           ///< fewer usable pairs: no rejection this frame

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("max_tracks", s.max_tracks, Limits::range(1, 5000));
    v.key("grid_cols", s.grid_cols, Limits::range(1, 50));
    v.key("grid_rows", s.grid_rows, Limits::range(1, 50));
    v.key("fast_threshold", s.fast_threshold, Limits::range(1, 255));
    v.key("min_distance_px", s.min_distance_px, Limits::nonNegative());
    v.key("klt_window_px", s.klt_window_px, Limits::range(5, 1001));
    v.key("klt_pyramid_levels", s.klt_pyramid_levels, Limits::range(0, 6));
    v.key("klt_max_iterations", s.klt_max_iterations, Limits::range(1, 200));
    v.key("forward_backward_check", s.forward_backward_check);
    v.key("fb_max_error_px", s.fb_max_error_px, Limits::positive());
    v.key("ransac", s.ransac);
    v.key("ransac_threshold_px", s.ransac_threshold_px, Limits::positive());
    v.key("ransac_max_angle_deg", s.ransac_max_angle_deg, Limits::range(1.0, 89.0));
    v.key("ransac_min_pairs", s.ransac_min_pairs, Limits::range(5, 10000));
    v.key("border_px", s.border_px, Limits::range(0, 100));
    v.key("equalize_histogram", s.equalize_histogram);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Interface of feature sources (the image tracker; the oracle source of oracle_features.h).
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
  // Not copyable: a copy would share (cv::Mat) and overwrite the pyramid buffers it reuses.
  KltFeatureTracker(const KltFeatureTracker&) = delete;
  KltFeatureTracker& operator=(const KltFeatureTracker&) = delete;

  TrackFrame process(const CameraFrame& frame) override;

  /// Turns on KLT mis-tracks (a degradation axis; off unless called).
  void setMistracks(const MistrackModel& model) { mistracks_ = model; }

 private:
  void detect(const cv::Mat& img, std::vector<Track>& tracks, int* added);
  // The previous frame's tracks followed into `pyramid` (KLT, the optional backward check, the
  // valid mask, mis-tracks when on, then the epipolar RANSAC); counts go into `out`.
  std::vector<Track> trackForward(const std::vector<cv::Mat>& pyramid, cv::Size image, TrackFrame& out);
  // Drops the epipolar outliers among tracked pairs (prev pixel, new pixel); returns the keep mask.
  std::vector<bool> epipolarInliers(const std::vector<Vec2>& prev_px, const std::vector<Vec2>& new_px,
                                    TrackFrame& out) const;

  FeatureTrackerConfig config_;
  FisheyeCamera camera_;
  cv::Mat valid_mask_;  // pixels inside the FoV, away from its border
  std::vector<cv::Mat> prev_pyramid_;
  std::vector<cv::Mat> spare_pyramid_;  // the pyramid before last, its buffers reused for the next
  cv::Mat image_;                       // the equalised frame (its buffer reused)
  std::vector<Track> prev_tracks_;
  uint64_t next_id_ = 1;
  std::optional<MistrackModel> mistracks_;  // degradation: none by default
};

}  // namespace msb
