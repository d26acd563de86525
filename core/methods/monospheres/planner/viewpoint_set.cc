#include "core/methods/monospheres/planner/viewpoint_set.h"

#include <algorithm>
#include <cmath>

#include "core/common/types.h"

namespace msb {

namespace {}

void ViewpointConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(relaxed_min_value <= min_value, "relaxed_min_value", "must not exceed min_value");
  c.require(
      frontier_view_limit == 0 || !vpb_new_frontiers, "frontier_view_limit",
      "cannot be combined with vpb_new_frontiers (both replace pose blocking); set it to 0 to use vpb_new_frontiers");
}

bool posesClose(const Vec3& p, double yaw, const Vec3& q, double qyaw, double distance_m, double angle_rad) {
  return (p - q).norm() <= distance_m && std::abs(wrapAngle(yaw - qyaw)) <= angle_rad;
}

ViewpointSet::ViewpointSet(const ViewpointConfig& config, uint64_t seed)
    : config_(checkValid(config)),
      rng_(seed, "viewpoints"),
      cos_half_fov_(std::cos(config_.fov_half_angle_deg * kDeg)) {}

ViewpointSet::View ViewpointSet::viewOf(const Vec3& p, double yaw) {
  return {p, Vec3(std::cos(yaw), std::sin(yaw), 0.0)};
}

bool ViewpointSet::sees(const View& v, const Frontier& f) const {
  const Vec3 ray = f.position - v.p;
  const double d = ray.norm();
  if (d < 1e-6 || d > config_.frontier_range_m) return false;
  if (config_.pinhole_view.on) {
    if (!inPinholeFrustum(v, ray)) return false;
  } else if (ray.dot(v.heading) < cos_half_fov_ * d) {
    return false;  // outside the useful field of view
  }
  return f.normal.dot(ray) < 0;  // not from its unknown side
}

bool ViewpointSet::inPinholeFrustum(const View& v, const Vec3& ray) const {
  // The published getVisiblePoints: in front of the level camera and projected by K strictly
  // inside the image (camera x to the right of the heading, y down).
  const double z = ray.dot(v.heading);
  if (z <= 0) return false;
  const double x = (ray.x() * v.heading.y() - ray.y() * v.heading.x()) / z, y = -ray.z() / z;
  const PinholeFrustum& f = config_.pinhole_view;
  return x > -f.left && x < f.right && y > -f.up && y < f.down;
}

std::vector<uint64_t> ViewpointSet::visibleFrontiers(const SphereMap& map, const View& v) const {
  std::vector<uint64_t> ids;
  for (uint64_t id : map.frontiersNear(v.p, config_.frontier_range_m))
    if (sees(v, map.frontiers().at(id))) ids.push_back(id);
  return ids;
}

void ViewpointSet::addMarker(const VisitedMarker& m) {
  markers_.push_back(m);
  marker_views_.push_back(viewOf(m.position, m.yaw_rad));
}

int ViewpointSet::value(const SphereMap& map, const Vec3& p, double yaw, uint64_t min_frontier_id) const {
  // With the view limit: markers close to this pose, whose frontiers do not count here.
  std::vector<const View*> close;
  const int limit = config_.frontier_view_limit;
  if (limit > 0)
    for (size_t i = 0; i < markers_.size(); ++i)
      if (posesClose(p, yaw, markers_[i].position, markers_[i].yaw_rad, config_.block_distance_m,
                     config_.block_angle_deg * kDeg))
        close.push_back(&marker_views_[i]);
  // The frontiers visible from the pose, then the view limit's tests (a count: the order in
  // which frontiers come does not matter, nor the view counts' cache it fills).
  const View view = viewOf(p, yaw);
  int n = 0;
  map.forEachFrontierNear(p, config_.frontier_range_m, [&](uint64_t id, const Frontier& f) {
    if (!sees(view, f)) return;
    if (id < min_frontier_id) return;  // older than a close visited marker (vpb_new_frontiers)
    if (limit > 0) {
      if (views(f, id) >= limit) return;  // retired: looked at often enough
      if (std::any_of(close.begin(), close.end(), [&](const View* m) { return sees(*m, f); }))
        return;  // already looked at from about here
    }
    ++n;
  });
  return n;
}

int ViewpointSet::views(const SphereMap& map, uint64_t id) const {
  if (config_.frontier_view_limit <= 0) return 0;
  return views(map.frontiers().at(id), id);
}

int ViewpointSet::views(const Frontier& f, uint64_t id) const {
  ViewCount& c = views_[id];
  for (; c.checked < markers_.size(); ++c.checked) c.views += sees(marker_views_[c.checked], f);
  return c.views;
}

int ViewpointSet::retiredFrontiers(const SphereMap& map) const {
  if (config_.frontier_view_limit <= 0) return 0;
  int n = 0;
  for (const auto& [id, f] : map.frontiers()) n += views(map, id) >= config_.frontier_view_limit;
  return n;
}

ViewpointSet::Block ViewpointSet::blocked(const Vec3& p, double yaw, double t_s, uint64_t goal_id,
                                          uint64_t* min_frontier_id) const {
  const double d = config_.block_distance_m, a = config_.block_angle_deg * kDeg;
  if (config_.vpb && config_.frontier_view_limit == 0)  // with the view limit markers block frontiers
    for (const auto& m : markers_) {
      if (!posesClose(p, yaw, m.position, m.yaw_rad, d, a)) continue;
      if (!config_.vpb_new_frontiers) return Block::kMarker;
      *min_frontier_id = std::max(*min_frontier_id, m.frontier_watermark);
    }
  if (goal_id) {
    const auto it = viewpoints_.find(goal_id);
    if (it != viewpoints_.end() && posesClose(p, yaw, it->second.position, it->second.yaw_rad, d, a))
      return Block::kGoalOrFailed;
  }
  for (const auto& [q, until] : blacklist_)
    if (t_s < until && (p - q).norm() <= config_.blacklist_radius_m) return Block::kGoalOrFailed;
  return Block::kNone;
}

int ViewpointSet::update(const SphereMap& map, const std::vector<uint64_t>& reachable, const Vec3& vehicle,
                         double vehicle_yaw, double t_s, uint64_t goal_id,
                         const std::function<bool(const Vec3&)>& allowed, bool relaxed) {
  const int min_value = relaxed ? config_.relaxed_min_value : config_.min_value;
  const double d = config_.block_distance_m, a = config_.block_angle_deg * kDeg;
  auto reach = [&](uint64_t sphere) { return std::binary_search(reachable.begin(), reachable.end(), sphere); };

  // Existing viewpoints: still on a reachable sphere, still valuable, not passed (VPB).
  for (auto it = viewpoints_.begin(); it != viewpoints_.end();) {
    Viewpoint& v = it->second;
    bool keep = map.spheres().count(v.sphere) && reach(v.sphere);
    if (keep && it->first != goal_id) {
      v.value = value(map, v.position, v.yaw_rad);
      keep = v.value >= min_value;
      if (keep && config_.vpb && posesClose(vehicle, vehicle_yaw, v.position, v.yaw_rad, d, a)) {
        addMarker({vehicle, vehicle_yaw, map.nextFrontierId()});
        ++passed_;
        keep = false;
      }
    }
    it = keep ? std::next(it) : viewpoints_.erase(it);
  }
  std::erase_if(blacklist_, [&](const auto& b) { return t_s >= b.second; });
  // View counts of frontiers the map has dropped are forgotten (ids are never reused).
  std::erase_if(views_, [&](const auto& e) { return !map.frontiers().count(e.first); });

  // New candidates at reachable sphere centres with a random yaw.
  int added = 0;
  if (reachable.empty()) return 0;
  std::vector<uint64_t> every;  // the published code's index into the whole map (ids ascending)
  if (config_.sample_anywhere)
    for (const auto& [id, s] : map.spheres()) every.push_back(id);
  const std::vector<uint64_t>& pool = config_.sample_anywhere ? every : reachable;
  for (int k = 0; k < config_.candidates; ++k) {
    const uint64_t sphere = pool[rng_.uniformInt(pool.size())];
    const double yaw = rng_.uniform(-M_PI, M_PI);
    const Vec3 p = map.spheres().at(sphere).centre;
    if (allowed && !allowed(p)) {
      ++rejected_.outside;
      continue;
    }
    uint64_t newer_than = 0;
    if (const Block b = blocked(p, yaw, t_s, goal_id, &newer_than); b != Block::kNone) {
      ++(b == Block::kMarker ? rejected_.visited : rejected_.blocked);
      continue;
    }
    const int val = value(map, p, yaw, newer_than);
    if (val < min_value) {
      // Refused because of visits: a newer-than bound, or retired frontiers it would otherwise see.
      const bool by_visits = newer_than > 0 || (config_.frontier_view_limit > 0 &&
                                                int(visibleFrontiers(map, viewOf(p, yaw)).size()) >= min_value);
      ++(by_visits ? rejected_.visited : val > 0 ? rejected_.low_value : rejected_.no_frontier);
      continue;
    }
    // Near an existing viewpoint: the better one stays (keeps the set sparse).
    bool dominated = false;
    std::vector<uint64_t> replaced;
    for (const auto& [id, v] : viewpoints_) {
      if (!posesClose(p, yaw, v.position, v.yaw_rad, d, a)) continue;
      if (v.value >= val || id == goal_id)
        dominated = true;
      else
        replaced.push_back(id);
    }
    if (dominated) {
      ++rejected_.dominated;
      continue;
    }
    for (uint64_t id : replaced) viewpoints_.erase(id);
    viewpoints_[next_id_] = {next_id_, p, yaw, val, sphere};
    ++next_id_;
    ++added;
  }
  return added;
}

void ViewpointSet::markReached(uint64_t id, const SphereMap& map, const Vec3& vehicle, double vehicle_yaw) {
  viewpoints_.erase(id);
  if (config_.vpb) addMarker({vehicle, vehicle_yaw, map.nextFrontierId()});
}

void ViewpointSet::markFailed(uint64_t id, double t_s) {
  const auto it = viewpoints_.find(id);
  if (it == viewpoints_.end()) return;
  blacklist_.emplace_back(it->second.position, t_s + config_.blacklist_duration_s);
  viewpoints_.erase(it);
}

}  // namespace msb
