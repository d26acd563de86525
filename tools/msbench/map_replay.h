// Replaying a recorded perception log through the sphere mapper (msbench map-replay, bench-map):
// the log read and checked, the camera its header names, and the mapper run at a rate.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera/fisheye_camera.h"
#include "core/eval/map_accuracy.h"
#include "core/eval/map_safety.h"
#include "core/geometry/world_truth.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "tools/results/perception_log.h"

namespace msb {

/// What a replay measured.
struct Replay {
  MapSafetyStats safety;
  std::string safety_rule;  ///< the rule the statistics used
  std::vector<MapUpdateStats> stats;
  std::vector<double> total_ms;
  std::vector<double> t;
  std::vector<int> spheres, obstacles, frontiers;
  long live_samples = 0, live_covered = 0;  // camera above 1 m inside the spheres of that moment
  // With ground truth: the obstacle points, each classified in the true frame of the update that
  // inserted it — all inserted, those DBOF deleted, those in the final map.
  PointPlacement inserted, dbof_deleted, final_obstacles;
};

/// Runs the mapper over the log at `rate_hz` (the frames at or after each period); with ground
/// truth, checks the map's safety (its Monte Carlo stream seeded here, once per replay).
Replay replay(const PerceptionLog& log, SphereMap& map, double rate_hz, const WorldTruth* truth = nullptr);

/// A log to replay: read and checked, with at least one frame (FileConfigError otherwise).
PerceptionLog readReplayableLog(const std::string& path);

/// The camera of a log, from its header (errors name the log file).
FisheyeCamera cameraFromHeader(const std::string& path, const nlohmann::json& header);

}  // namespace msb
