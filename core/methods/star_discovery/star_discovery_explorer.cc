#include "core/methods/star_discovery/star_discovery_explorer.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <tuple>

namespace msb {

void StarDiscoveryConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

Star planStar(const GridPathPlanner& planner, const Vec3& origin, const StarDiscoveryConfig& config) {
  Star best;
  best.origin = origin;
  best.size_m = -1.0;
  const double step = 0.5 * config.map.resolution_m;
  for (int h = 0; h < config.heights; ++h) {
    // Heights in the order 0, +1, -1, +2, ... steps (ties keep the origin's own height).
    const int k = (h + 1) / 2 * (h % 2 ? 1 : -1);
    const Vec3 o = origin + Vec3(0, 0, k * config.height_step_m);
    if (!planner.traversable(o)) continue;
    Star star;
    star.origin = o;
    star.size_m = 0.0;
    for (int r = 0; r < config.rays; ++r) {
      const double a = 2.0 * M_PI * r / config.rays;
      const Vec3 dir(std::cos(a), std::sin(a), 0.0);
      double reach = 0.0;  // farthest traversable distance along the ray, no gap on the way
      for (double t = step; t <= config.max_ray_m + 1e-9; t += step) {
        if (!planner.traversable(o + t * dir)) break;
        reach = t;
      }
      if (reach < config.min_ray_m) continue;
      star.ends.push_back(o + reach * dir);
      star.size_m += reach;
    }
    if (star.size_m > best.size_m) best = star;
  }
  if (best.size_m < 0) best.size_m = 0.0;
  return best;
}

LineOfSightGrid::LineOfSightGrid(const GridMap& map, const Aabb& box) : res_(map.config().resolution_m) {
  // Cells aligned with the octree: cell centres at (i + 0.5) res.
  origin_ = (box.min / res_).array().floor().matrix() * res_;
  nx_ = std::max(1, int(std::ceil((box.max.x() - origin_.x()) / res_)));
  ny_ = std::max(1, int(std::ceil((box.max.y() - origin_.y()) / res_)));
  nz_ = std::max(1, int(std::ceil((box.max.z() - origin_.z()) / res_)));
  free_.assign(size_t(nx_) * ny_ * nz_, 0);
  for (int k = 0; k < nz_; ++k)
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i)
        free_[(size_t(k) * ny_ + j) * nx_ + i] = map.occupancy(origin_ + res_ * Vec3(i + 0.5, j + 0.5, k + 0.5)) == 0;
}

bool LineOfSightGrid::cellOf(const Vec3& p, int* i, int* j, int* k) const {
  *i = int(std::floor((p.x() - origin_.x()) / res_));
  *j = int(std::floor((p.y() - origin_.y()) / res_));
  *k = int(std::floor((p.z() - origin_.z()) / res_));
  return *i >= 0 && *j >= 0 && *k >= 0 && *i < nx_ && *j < ny_ && *k < nz_;
}

bool LineOfSightGrid::free(const Vec3& p) const {
  int i, j, k;
  return cellOf(p, &i, &j, &k) && free_[(size_t(k) * ny_ + j) * nx_ + i];
}

bool LineOfSightGrid::clear(const Vec3& a, const Vec3& b) const {
  const double len = (b - a).norm();
  const int n = std::max(1, int(std::ceil(len / (0.5 * res_))));
  for (int s = 0; s <= n; ++s)
    if (!free(a + (b - a) * (double(s) / n))) return false;
  return true;
}

std::vector<Vec3> interestingCells(const GridMap& map, const GridPathPlanner& planner, const Aabb& box,
                                   const std::vector<Vec3>& origins, double range_m) {
  const LineOfSightGrid los(map, box);
  const double res = map.config().resolution_m;
  const Vec3 lo = (box.min / res).array().floor().matrix() * res;
  std::vector<Vec3> out;
  for (double z = lo.z() + 0.5 * res; z < box.max.z(); z += res)
    for (double y = lo.y() + 0.5 * res; y < box.max.y(); y += res)
      for (double x = lo.x() + 0.5 * res; x < box.max.x(); x += res) {
        const Vec3 c(x, y, z);
        if (!planner.traversable(c) || !los.free(c)) continue;
        bool seen = false;
        for (const Vec3& o : origins)
          if ((c - o).norm() <= range_m && los.clear(o, c)) {
            seen = true;
            break;
          }
        if (!seen) out.push_back(c);
      }
  return out;
}

std::vector<Vec3> largestComponent(const std::vector<Vec3>& cells, double resolution_m) {
  // Integer cell coordinates, sorted for lookups; flood fill in cell order (deterministic).
  using Key = std::tuple<long, long, long>;
  auto keyOf = [&](const Vec3& p) {
    return Key{std::lround(std::floor(p.x() / resolution_m)), std::lround(std::floor(p.y() / resolution_m)),
               std::lround(std::floor(p.z() / resolution_m))};
  };
  std::vector<std::pair<Key, size_t>> keys;
  for (size_t i = 0; i < cells.size(); ++i) keys.push_back({keyOf(cells[i]), i});
  std::sort(keys.begin(), keys.end());
  std::vector<int> label(cells.size(), -1);
  std::vector<size_t> best;
  for (size_t seed = 0; seed < cells.size(); ++seed) {
    if (label[seed] >= 0) continue;
    std::vector<size_t> comp;
    std::deque<size_t> queue{seed};
    label[seed] = int(seed);
    while (!queue.empty()) {
      const size_t c = queue.front();
      queue.pop_front();
      comp.push_back(c);
      const auto [x, y, z] = keyOf(cells[c]);
      for (long dz = -1; dz <= 1; ++dz)
        for (long dy = -1; dy <= 1; ++dy)
          for (long dx = -1; dx <= 1; ++dx) {
            const Key n{x + dx, y + dy, z + dz};
            const auto it = std::lower_bound(keys.begin(), keys.end(), std::pair<Key, size_t>{n, 0});
            if (it == keys.end() || it->first != n || label[it->second] >= 0) continue;
            label[it->second] = int(seed);
            queue.push_back(it->second);
          }
    }
    if (comp.size() > best.size()) best = comp;
  }
  std::sort(best.begin(), best.end());
  std::vector<Vec3> out;
  for (size_t i : best) out.push_back(cells[i]);
  return out;
}

StarDiscoveryExplorer::StarDiscoveryExplorer(const StarDiscoveryConfig& config, const ExplorerContext& context)
    : config_(checkValid(config)),
      context_(context),
      map_(config.map),
      planner_(config.planner, context.exploration_box, config.map.resolution_m),
      candidate_rng_(context.seed, "star_candidates"),
      takeoff_(context.start, config) {}

void StarDiscoveryExplorer::observe(const SlamPointsFrame& frame) {
  counters_[StarDiscoveryCounter::kMapPoints] += map_.insert(frame).points;
  map_changed_ = true;
}

void StarDiscoveryExplorer::rebuildPlanner() {
  if (!map_changed_) return;
  planner_.rebuild(map_);
  map_changed_ = false;
}

PathCommand StarDiscoveryExplorer::command(const VehicleState& s, std::vector<Waypoint> w) {
  sent_ = true;
  return sendPath(s, std::move(w), last_path_, counters_[StarDiscoveryCounter::kPathsSent]);
}

bool StarDiscoveryExplorer::pathBlocked(const Vec3& from) const {
  return pathNearOccupied(map_, last_path_, from, config_.check_ahead_m, config_.check_clearance_m);
}

std::optional<PathCommand> StarDiscoveryExplorer::startStar(const VehicleState& s) {
  rebuildPlanner();
  const Star star = planStar(planner_, s.reference.position_m, config_);
  origins_.push_back(star.origin);
  ++counters_[StarDiscoveryCounter::kStars];
  counters_[StarDiscoveryCounter::kStarRays] += double(star.ends.size());
  phase_ = Phase::kStar;
  // Out and back along every ray, the camera 90° to the motion.
  std::vector<Waypoint> w{{star.origin, std::nullopt}};
  for (const Vec3& end : star.ends) {
    const Vec3 d = end - star.origin;
    const double heading = std::atan2(d.y(), d.x()) + 0.5 * M_PI;
    w.push_back({end, heading});
    w.push_back({star.origin, heading});
  }
  return command(s, std::move(w));
}

std::optional<PathCommand> StarDiscoveryExplorer::chooseNextOrigin(const VehicleState& s) {
  rebuildPlanner();
  ++counters_[StarDiscoveryCounter::kGlobalSteps];
  const std::vector<Vec3> interesting =
      interestingCells(map_, planner_, context_.exploration_box, origins_, config_.los_range_m);
  counters_[StarDiscoveryCounter::kInterestingCells] = double(interesting.size());
  const std::vector<Vec3> component = largestComponent(interesting, config_.map.resolution_m);
  std::vector<std::pair<double, Vec3>> ranked;
  if (!component.empty()) {
    // Random candidates of the component; the one allowing the largest star first.
    for (int c = 0; c < config_.candidates; ++c) {
      const size_t i = std::min(component.size() - 1, size_t(candidate_rng_.uniform(0.0, double(component.size()))));
      ranked.push_back({planStar(planner_, component[i], config_).size_m, component[i]});
    }
  } else {
    // Every free cell is in sight of an origin (a sparse map's free space is mostly rays from
    // the camera positions): the paper does not say what then; we go on from the traversable
    // cells farthest from every origin, so the method keeps moving while free space grows.
    ++counters_[StarDiscoveryCounter::kFallbackSteps];
    for (const Vec3& c : interestingCells(map_, planner_, context_.exploration_box, {}, config_.los_range_m)) {
      double nearest = 1e9;
      for (const Vec3& o : origins_) nearest = std::min(nearest, (c - o).norm());
      if (nearest >= 2.0 * config_.min_ray_m) ranked.push_back({nearest, c});
    }
    if (ranked.empty()) {
      ++counters_[StarDiscoveryCounter::kHolds];  // nowhere to go yet: hold, look again later
      phase_ = Phase::kHold;
      hold_until_s_ = s.t_s + config_.retry_period_s;
      return command(s, {{s.reference.position_m, std::nullopt}});
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (ranked.size() > size_t(config_.candidates)) ranked.resize(size_t(config_.candidates));
  for (const auto& [size, cell] : ranked) {
    const std::optional<GridPath> path = planner_.plan(s.reference.position_m, cell);
    if (!path || !path->reaches_goal || path->points.size() < 2) continue;
    target_ = cell;
    phase_ = Phase::kTransit;
    last_plan_s_ = transit_since_s_ = s.t_s;
    return command(s, pathWaypoints(path->points));
  }
  // No candidate reachable: a star from here if this spot is not an origin yet, else hold and
  // look again after retry_period_s (the map may have grown).
  ++counters_[StarDiscoveryCounter::kTransitsFailed];
  const Vec3 here = s.reference.position_m;
  const bool known = std::any_of(origins_.begin(), origins_.end(),
                                 [&](const Vec3& o) { return (o - here).norm() < config_.min_ray_m; });
  if (!known) return startStar(s);
  ++counters_[StarDiscoveryCounter::kHolds];
  phase_ = Phase::kHold;
  hold_until_s_ = s.t_s + config_.retry_period_s;
  return command(s, {{here, std::nullopt}});
}

std::optional<PathCommand> StarDiscoveryExplorer::plan(const VehicleState& s) {
  switch (phase_) {
    case Phase::kTakeoff:
      if (auto w = takeoff_.step(s.path_finished)) return command(s, std::move(*w));
      if (!takeoff_.done()) return std::nullopt;
      {
        // The look-around: a full turn on the spot.
        phase_ = Phase::kLookAround;
        const Vec3 p = s.reference.position_m;
        std::vector<Waypoint> w;
        const int steps = int(std::ceil(360.0 / config_.look_around_step_deg));
        for (int k = 1; k <= steps; ++k) w.push_back({p, s.reference.yaw_rad + k * 2.0 * M_PI / steps});
        return command(s, std::move(w));
      }
    case Phase::kLookAround:
      if (s.path_finished) return startStar(s);
      return std::nullopt;
    case Phase::kStar:
      if (!s.path_finished && pathBlocked(s.reference.position_m)) {
        ++counters_[StarDiscoveryCounter::kBlockedStops];
        phase_ = Phase::kGlobal;
        return command(s, {{s.reference.position_m, std::nullopt}});
      }
      if (s.path_finished) phase_ = Phase::kGlobal;
      return std::nullopt;
    case Phase::kGlobal:
      if (s.path_finished) return chooseNextOrigin(s);
      return std::nullopt;
    case Phase::kTransit: {
      if ((s.T_W_B.translation() - *target_).norm() <= 1.0 && s.path_finished) {
        ++counters_[StarDiscoveryCounter::kTransitsReached];
        return startStar(s);
      }
      if (s.t_s - transit_since_s_ > config_.transit_timeout_s) {
        ++counters_[StarDiscoveryCounter::kTransitsFailed];
        phase_ = Phase::kGlobal;
        return command(s, {{s.reference.position_m, std::nullopt}});
      }
      const bool blocked = !s.path_finished && pathBlocked(s.reference.position_m);
      if (blocked) ++counters_[StarDiscoveryCounter::kBlockedStops];
      if (!blocked && !s.path_finished && s.t_s - last_plan_s_ < config_.replan_period_s - 1e-9) return std::nullopt;
      // Re-plan to the target (the map changed on the way, or the path ended short of it).
      last_plan_s_ = s.t_s;
      rebuildPlanner();
      const std::optional<GridPath> path = planner_.plan(s.reference.position_m, *target_);
      if (!path || !path->reaches_goal || path->points.size() < 2) {
        ++counters_[StarDiscoveryCounter::kTransitsFailed];
        if (s.path_finished || blocked) {
          phase_ = Phase::kGlobal;  // a new target from here
          return command(s, {{s.reference.position_m, std::nullopt}});
        }
        return std::nullopt;
      }
      return command(s, pathWaypoints(path->points));
    }
    case Phase::kHold:
      if (s.t_s >= hold_until_s_ && s.path_finished) return chooseNextOrigin(s);
      return std::nullopt;
  }
  return std::nullopt;
}

std::vector<FreeSpaceElement> StarDiscoveryExplorer::freeSpace() const { return freeLeaves(map_); }

ExplorerSnapshot StarDiscoveryExplorer::snapshot() const {
  ExplorerSnapshot snap = gridSnapshot(map_, target_, last_path_);
  for (const Vec3& o : origins_) snap.visited.push_back({o, 0.0});
  return snap;
}

std::map<std::string, double> StarDiscoveryExplorer::counters() const {
  Counters<StarDiscoveryCounter> c = counters_;
  c[StarDiscoveryCounter::kLeaves] = double(map_.tree().getNumLeafNodes());
  c[StarDiscoveryCounter::kOrigins] = double(origins_.size());
  return c.toMap();
}

}  // namespace msb
