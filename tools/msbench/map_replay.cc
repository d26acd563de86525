#include "tools/msbench/map_replay.h"

#include "tools/msbench/interrupt.h"

#include <cmath>
#include <map>
#include <optional>

#include "core/common/config_check.h"
#include "core/common/wall_time.h"

namespace msb {

namespace {

// The obstacle points of one update against the truth: the new ones classified in the true frame
// of this moment (ids only grow), DBOF's deletions counted by the class they entered with.
void classifyObstacles(const SphereMap& map, const WorldTruth& truth, const Pose& T_true_est, const MapUpdateStats& st,
                       std::map<uint64_t, Placement>& placement, Replay& r) {
  for (uint64_t id : st.dbof_deleted_ids)
    if (auto it = placement.find(id); it != placement.end()) countPlacement(r.dbof_deleted, it->second);
  const uint64_t newest_known = placement.empty() ? 0 : placement.rbegin()->first;
  for (auto it = map.obstacles().upper_bound(newest_known); it != map.obstacles().end(); ++it) {
    const Placement c = placementOf(truth, T_true_est * it->second.position);
    placement[it->first] = c;
    countPlacement(r.inserted, c);
  }
}

}  // namespace

// Runs the mapper over the log at the given rate (frames at or after each period); with ground
// truth, checks the map's safety (its Monte Carlo stream seeded here, once per replay).
Replay replay(const PerceptionLog& log, SphereMap& map, double rate_hz, const WorldTruth* truth) {
  Replay r;
  std::optional<MapSafetyCheck> safety;
  if (truth) safety.emplace(*truth, 0);
  double next_t = -1e9;
  std::map<uint64_t, Placement> placement;  // obstacle id -> placementOf at insertion
  for (const auto& f : log.frames) {
    throwIfInterrupted();  // a safe point: nothing of this frame is in the map yet
    // Corridor at the time: is the camera inside the free space the map has at that moment?
    if (f.T_W_C_truth.translation().z() >= 1.0) {
      ++r.live_samples;
      r.live_covered += !map.spheresNear(f.points.T_W_C.translation(), 0.0).empty();
    }
    if (f.points.t_s + 1e-9 < next_t) continue;
    next_t = f.points.t_s + 1.0 / rate_hz - 1e-6;
    const auto t0 = WallClock::now();
    r.stats.push_back(map.update(f.points));
    r.total_ms.push_back(msSince(t0));
    // Map safety: every sphere created or grown, against the ground truth of that moment.
    if (safety) {
      const Pose T_true_est = f.T_W_C_truth * f.points.T_W_C.inverse();
      for (uint64_t id : r.stats.back().changed_spheres) {
        const Sphere& s = map.spheres().at(id);
        safety->checkSphere(s.centre, s.radius, T_true_est);
      }
      classifyObstacles(map, *truth, T_true_est, r.stats.back(), placement, r);
    }
    r.t.push_back(f.points.t_s);
    r.spheres.push_back(int(map.spheres().size()));
    r.obstacles.push_back(int(map.obstacles().size()));
    r.frontiers.push_back(int(map.frontiers().size()));
  }
  if (safety) r.safety = safety->stats(), r.safety_rule = safety->rule();
  for (const auto& [id, o] : map.obstacles())
    if (auto it = placement.find(id); it != placement.end()) countPlacement(r.final_obstacles, it->second);
  return r;
}

// A log to replay: read and checked, with at least one frame.
PerceptionLog readReplayableLog(const std::string& path) {
  PerceptionLog log = PerceptionLog::read(path);
  if (log.frames.empty()) throw FileConfigError(path + ": the log holds a header and no frames: nothing to replay");
  return log;
}

// The camera of a log, from its header (errors name the log file).
FisheyeCamera cameraFromHeader(const std::string& path, const nlohmann::json& h) {
  FisheyeCameraConfig c;
  if (h.contains("camera_scale")) {
    if (!h["camera_scale"].is_number() || !std::isfinite(h["camera_scale"].get<double>()))
      throw UsageError(path + ": log header 'camera_scale': expected a number");
    c.scale = h["camera_scale"].get<double>();
  }
  try {
    return FisheyeCamera(c);
  } catch (const ConfigError& e) {
    throw UsageError(path + ": log header: " + e.what());
  }
}

}  // namespace msb
