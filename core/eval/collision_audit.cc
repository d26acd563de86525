#include "core/eval/collision_audit.h"
#include "core/eval/slam_point_truth.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

namespace msb {

namespace {

// True if p lies in the element (a sphere, or a cell's cube for square footprints).
bool contains(const FreeSpaceElement& e, const Vec3& p) {
  if (e.footprint == FreeSpaceElement::Footprint::kSquare) return ((p - e.centre).cwiseAbs().array() <= e.radius).all();
  return (p - e.centre).norm() <= e.radius;
}

}  // namespace

CollisionAudit auditCollision(const CollisionAuditInput& in, const WorldTruth& truth,
                              const CollisionAuditThresholds& th) {
  CollisionAudit a;
  a.slam_points_on_object = in.slam_points_on_object;
  a.slam_points_on_part = in.slam_points_on_part;
  a.vio_drift_m = in.vio_drift_m;
  a.commanded_speed_mps = in.commanded_speed_mps;
  a.since_last_path_s = in.since_last_path_s;
  const Vec3 contact_est = in.T_true_from_est.inverse() * in.contact_W;
  if (in.map) {
    // The object's map points (true frame after the drift at contact) and the nearest point.
    for (const Vec3& p_est : in.map->obstacles) {
      const double d = (p_est - contact_est).norm();
      a.nearest_map_point_m = a.nearest_map_point_m < 0 ? d : std::min(a.nearest_map_point_m, d);
      const Vec3 p = in.T_true_from_est * p_est;
      for (const Shape& s : truth.shapes())
        if (s.object == in.object && std::abs(s.signedDistance(p)) <= th.on_object_m) {
          ++a.map_points_on_object;
          break;
        }
    }
    // Free space at the contact, and since when.
    for (const FreeSpaceElement& e : in.map->free_space) {
      if (!contains(e, contact_est)) continue;
      a.inside_free_space = true;
      if (in.free_space_first_seen_s)
        if (const auto it = in.free_space_first_seen_s->find(e.id); it != in.free_space_first_seen_s->end())
          a.free_space_since_s = a.free_space_since_s ? std::min(*a.free_space_since_s, it->second) : it->second;
    }
  }
  // The free space at the contact where it was carved: the correction of its first sample.
  if (a.free_space_since_s && in.true_from_est_history && !in.true_from_est_history->empty()) {
    const auto& h = *in.true_from_est_history;
    auto it = std::upper_bound(h.begin(), h.end(), *a.free_space_since_s,
                               [](double t, const std::pair<double, Pose>& e) { return t < e.first; });
    const Pose& then = it == h.begin() ? h.front().second : std::prev(it)->second;
    const Vec3 carved_W = then * contact_est;
    a.carved_clearance_m = truth.distance(carved_W);
    a.drift_since_carved_m = (carved_W - in.contact_W).norm();
  }
  const bool drifted_onto =
      a.carved_clearance_m && *a.carved_clearance_m > th.clearance_m && *a.drift_since_carved_m > th.clearance_m;
  if (a.slam_points_on_part == 0)
    a.cause = "unseen";
  else if (a.nearest_map_point_m >= 0 && a.nearest_map_point_m < th.clearance_m)
    a.cause = "planner";
  else if (drifted_onto)
    a.cause = "drift";
  else if (a.map_points_on_object == 0 || a.inside_free_space)
    a.cause = "seen-but-freed";
  else if (a.vio_drift_m > th.clearance_m)
    a.cause = "drift";
  else
    a.cause = "other";
  return a;
}

void CollisionAuditRecorder::addFrame(const SlamPointsFrame& points, const Pose& T_W_C_true, int64_t pose_tick) {
  if (pose_tick != points.tick)
    throw std::logic_error("collision audit: SLAM points of tick " + std::to_string(points.tick) +
                           " paired with the true camera pose of tick " + std::to_string(pose_tick));
  // New points are anchored at the frame that made them (their anchor tick is the frame's).
  for (const SlamPoint& p : points.points)
    if (p.anchor_tick == points.tick && audited_tracks_.insert(p.track_id).second) {
      const PointTruth pt = evaluatePoint(p, T_W_C_true, truth_, camera_);
      if (!pt.has_surface) continue;
      ++slam_points_by_object_[truth_.shapes()[pt.shape].object];
      ++slam_points_by_geom_[truth_.shapes()[pt.shape].name];
    }
}

void CollisionAuditRecorder::addSample(double t_s, const std::vector<FreeSpaceElement>& free_space,
                                       const Pose& true_from_est) {
  for (const FreeSpaceElement& e : free_space) free_space_first_seen_s_.emplace(e.id, t_s);
  true_from_est_history_.emplace_back(t_s, true_from_est);
}

CollisionAuditInput CollisionAuditRecorder::input(const std::string& world_geom) const {
  CollisionAuditInput in;
  if (const Shape* hit = truth_.shapeNamed(world_geom)) in.object = hit->object;
  auto count = [](const std::map<std::string, int>& m, const std::string& k) {
    const auto it = m.find(k);
    return it == m.end() ? 0 : it->second;
  };
  in.slam_points_on_object = in.object.empty() ? 0 : count(slam_points_by_object_, in.object);
  in.slam_points_on_part = count(slam_points_by_geom_, world_geom);
  in.free_space_first_seen_s = &free_space_first_seen_s_;
  in.true_from_est_history = &true_from_est_history_;
  return in;
}

}  // namespace msb
