#include "tools/results/vio_evaluation.h"

#include <algorithm>
#include <cstdio>

#include "core/eval/slam_point_truth.h"
#include "tools/results/flight_records.h"
#include "tools/results/provenance.h"

namespace msb {

// Adds one perception frame to the statistics: the points by distance, and against the ground
// truth (when the world has it) their surfaces and errors; the frame's line of frames.csv.
void addSample(VioStats& st, const PerceptionSample& s, const std::optional<WorldTruth>& truth,
               const FisheyeCamera& camera, std::map<int64_t, Pose>& gt_camera) {
  gt_camera[s.frame.tick] = s.frame.T_W_C;
  std::vector<double> frame_errors;
  // The premise of OVDE (seed paper §III-B): how far the points the mapper gets lie.
  for (const auto& p : s.points.points) {
    const double d = (p.p_W - s.points.T_W_C.translation()).norm();
    int band = 0;
    while (band + 1 < kBins && d >= kBinEdges[band + 1]) ++band;
    ++st.points_by_distance[band];
  }
  if (truth) {
    for (const auto& p : s.points.points) {
      const PointTruth t = evaluatePoint(p, gt_camera.at(p.anchor_tick), *truth, camera);
      ++st.point_samples;
      // Spurious near points: closer than 1 m to the camera and not on a surface (no surface
      // along the ray, or more than 0.3 m off it).
      if ((p.p_W - s.points.T_W_C.translation()).norm() < 1.0) {
        ++st.near_points;
        st.spurious_near += !t.has_surface || (t.interior && t.error_m > 0.3);
      }
      if (!t.has_surface) {
        ++st.no_surface;
        ++st.points_by_surface["none"];
        continue;
      }
      ++st.points_by_surface[surfaceClass(truth->shapes()[t.shape])];
      st.textureless += t.kind == ObstacleKind::kTextureless;
      st.textureless_interior += t.textureless_interior;
      st.thin += t.kind == ObstacleKind::kThin;
      if (!t.interior) {  // silhouette: no single true surface to compare with
        ++st.silhouette;
        continue;
      }
      st.point_ids_by_shape[truth->shapes()[t.shape].name].insert(p.track_id);
      int bin = 0;
      while (bin + 1 < kBins && t.true_depth_m >= kBinEdges[bin + 1]) ++bin;
      st.errors[bin].push_back(t.error_m);
      st.depth_std[bin].push_back(p.depth_std_m);
      frame_errors.push_back(t.error_m);
    }
  }
  ++st.frames;
  st.ransac_tested += s.tracks.ransac_tested;
  st.ransac_rejected += s.tracks.ransac_rejected;
  st.tracks_sum += s.tracks.tracks.size();
  st.points_sum += s.points.points.size();
  st.min_tracks = std::min(st.min_tracks, int(s.tracks.tracks.size()));
  st.tracker_ms += s.tracker_ms;
  st.tri_ms += s.triangulation_ms;
  st.render_ms += s.render_ms;
  char line[256];
  std::snprintf(line, sizeof(line), "%.3f,%zu,%d,%d,%zu,%.4f,%.3f,%.3f,%.3f\n", s.frame.t_s, s.tracks.tracks.size(),
                s.tracks.new_tracks, s.tracks.lost_tracks, s.points.points.size(), percentile(frame_errors, 0.5),
                s.tracker_ms, s.triangulation_ms, s.render_ms);
  st.csv += line;
}

// summary.json: the statistics of the flight.
nlohmann::json summaryJson(const VioStats& st, const FlightResult& r, const FlightSpec& spec, bool truth) {
  const double n = std::max(1, st.frames);
  nlohmann::json bins = nlohmann::json::array();
  for (int b = 0; b < kBins; ++b) {
    char label[32];
    std::snprintf(label, sizeof(label), b + 1 < kBins ? "%g-%g m" : ">%g m", kBinEdges[b], kBinEdges[b + 1]);
    bins.push_back({{"bin", label},
                    {"samples", st.errors[b].size()},
                    {"median_error_m", percentile(st.errors[b], 0.5)},
                    {"p90_error_m", percentile(st.errors[b], 0.9)},
                    {"median_predicted_depth_std_m", percentile(st.depth_std[b], 0.5)}});
  }
  const double ps = std::max<long>(1, st.point_samples);
  nlohmann::json by_distance = nlohmann::json::object(), by_surface = nlohmann::json::object();
  for (int b = 0; b < kBins; ++b) by_distance[bins[b]["bin"].get<std::string>()] = st.points_by_distance[b] / n;
  for (const auto& [surface, count] : st.points_by_surface) by_surface[surface] = count / n;
  nlohmann::json by_shape = nlohmann::json::object();
  for (const auto& [shape, ids] : st.point_ids_by_shape) by_shape[shape] = ids.size();
  nlohmann::json j = {
      {"status", runStatusName(r.status)},
      {"world", spec.world_name.empty() ? spec.world_path : spec.world_name},
      {"sim_time_s", r.sim_time_s},
      {"frames", st.frames},
      {"mean_tracks_per_frame", st.tracks_sum / n},
      {"min_tracks_per_frame", st.frames ? st.min_tracks : 0},
      {"mean_slam_points_per_frame", st.points_sum / n},
      {"point_error_by_distance", bins},
      {"slam_points_per_frame_by_distance", by_distance},
      {"slam_points_per_frame_by_surface", truth ? by_surface : nlohmann::json(nullptr)},
      {"distinct_slam_points_by_shape", truth ? by_shape : nlohmann::json(nullptr)},
      {"ground_truth", bool(truth)},
      {"textureless_point_share", truth ? nlohmann::json(st.textureless_interior / ps) : nlohmann::json(nullptr)},
      {"textureless_incl_silhouette_point_share",
       truth ? nlohmann::json(st.textureless / ps) : nlohmann::json(nullptr)},
      {"thin_point_share", truth ? nlohmann::json(st.thin / ps) : nlohmann::json(nullptr)},
      {"no_surface_point_share", truth ? nlohmann::json(st.no_surface / ps) : nlohmann::json(nullptr)},
      {"silhouette_point_share", truth ? nlohmann::json(st.silhouette / ps) : nlohmann::json(nullptr)},
      {"ransac_rejected_share", double(st.ransac_rejected) / double(std::max<long>(1, st.ransac_tested))},
      {"near_point_share", truth ? nlohmann::json(st.near_points / ps) : nlohmann::json(nullptr)},
      {"spurious_near_point_share", truth ? nlohmann::json(st.spurious_near / ps) : nlohmann::json(nullptr)},
      {"distance_flown_m", r.distance_flown_m},
      {"final_drift_m", r.final_drift_m},
      {"drift_percent_of_distance", r.distance_flown_m > 0 ? 100 * r.final_drift_m / r.distance_flown_m : 0.0},
      {"tracker_ms_per_frame", st.tracker_ms / n},
      {"triangulation_ms_per_frame", st.tri_ms / n},
      {"render_ms_per_frame", st.render_ms / n},
      {"wall_time_s", r.wall_time_s},
      {"trajectory_hash", hexHash(r.trajectory_hash)},
      {"versions", versionInfo()}};
  if (r.collision)
    j["collision"] = {{"t_s", r.collision->t_s},
                      {"vehicle_geom", r.collision->vehicle_geom},
                      {"world_geom", r.collision->world_geom},
                      {"vehicle_position_m",
                       {r.collision->vehicle_position_m.x(), r.collision->vehicle_position_m.y(),
                        r.collision->vehicle_position_m.z()}}};
  return j;
}

}  // namespace msb
