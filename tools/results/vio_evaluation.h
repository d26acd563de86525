// vio-eval's evaluation (`msbench vio-eval`, docs/perception.md): what perception produced for
// each camera frame of a scripted flight, against the world's ground truth when it has one —
// tracks and SLAM points per frame, the points by distance and by the surface they lie on, their
// errors by true depth, spurious near points, the cost of tracking and triangulation — gathered
// frame by frame and written as summary.json and frames.csv. The command flies and draws; this
// evaluates.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera/fisheye_camera.h"
#include "core/geometry/world_truth.h"
#include "core/perception/feature_tracker.h"
#include "tools/engine/closed_loop.h"
#include "tools/engine/flight_spec.h"

namespace msb {

/// Distance bins for the point-error statistics (metres, by ground-truth depth).
inline constexpr double kBinEdges[] = {0, 5, 10, 20, 40, 1e9};
inline constexpr int kBins = 5;

/// What perception produced for one camera frame.
struct PerceptionSample {
  const CameraFrame& frame;
  const TrackFrame& tracks;
  const SlamPointsFrame& points;
  double tracker_ms, triangulation_ms, render_ms;
};

/// Running statistics of the evaluation.
struct VioStats {
  std::vector<double> errors[kBins], depth_std[kBins];
  long point_samples = 0, textureless = 0, textureless_interior = 0, thin = 0, no_surface = 0, silhouette = 0;
  long ransac_tested = 0, ransac_rejected = 0;  // tracked pairs tested / dropped as epipolar outliers
  long near_points = 0, spurious_near = 0;      // points < 1 m from the camera / of those, on no surface
  double tracks_sum = 0, points_sum = 0, tracker_ms = 0, tri_ms = 0, render_ms = 0;
  double points_by_distance[kBins] = {};            // SLAM points summed over frames, by distance from the camera
  std::map<std::string, double> points_by_surface;  // ... by the class of the surface hit (ground truth)
  /// Distinct SLAM points (track ids) on each shape's interior (ground truth), by shape name.
  std::map<std::string, std::set<uint64_t>> point_ids_by_shape;
  int frames = 0, min_tracks = 1 << 30;
  std::string csv =
      "t,tracks,new_tracks,lost_tracks,slam_points,median_error_m,tracker_ms,triangulation_ms,render_ms\n";
};

/// Adds one perception frame to the statistics: the points by distance, and against the ground
/// truth (when the world has it) their surfaces and errors; the frame's line of frames.csv.
/// `gt_camera` collects the true camera pose of every frame (the anchors of later points).
void addSample(VioStats& st, const PerceptionSample& s, const std::optional<WorldTruth>& truth,
               const FisheyeCamera& camera, std::map<int64_t, Pose>& gt_camera);

/// summary.json: the statistics of the flight.
nlohmann::json summaryJson(const VioStats& st, const FlightResult& r, const FlightSpec& spec, bool truth);

}  // namespace msb
