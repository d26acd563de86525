#include "core/methods/monospheres/planner/monospheres_explorer.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/common/types.h"

namespace msb {

namespace {

// Cuts a waypoint list at arc length `max_len` from `from` (the cut point keeps no heading
// unless the cut falls exactly on a waypoint).
std::vector<Waypoint> cutAt(const Vec3& from, const std::vector<Waypoint>& w, double max_len) {
  std::vector<Waypoint> out;
  Vec3 prev = from;
  double s = 0;
  for (const auto& wp : w) {
    const double len = (wp.position_m - prev).norm();
    if (s + len > max_len && len > 1e-9) {
      out.push_back({prev + (max_len - s) / len * (wp.position_m - prev), wp.heading_rad});
      return out;
    }
    out.push_back(wp);
    s += len;
    prev = wp.position_m;
  }
  return out;
}
}  // namespace

void MonoSpheresPlannerConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

void MonoSpheresConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(planner.safety.r_safe_m > map.r_min_m, "planner.safety.r_safe_m", "must be larger than map.r_min_m");
}

namespace {
// The planner's search uses the map's minimum radius: one quantity, one key. The published
// code's switches reach the parts they change.
MonoSpheresConfig withSharedKeys(MonoSpheresConfig c, const FisheyeCamera& camera) {
  c.planner.safety.r_min_m = c.map.r_min_m;
  const ReferenceCodeConfig& rc = c.reference_code;
  c.planner.safety.inverted = rc.safety_cost_inverted;
  c.planner.viewpoints.sample_anywhere = rc.viewpoints_anywhere;
  c.map.pinhole_sample_rays = rc.pinhole_rays;
  if (rc.pinhole_rays)
    c.planner.viewpoints.pinhole_view = {true, camera.cx() / camera.fx(), (camera.width() - camera.cx()) / camera.fx(),
                                         camera.cy() / camera.fy(), (camera.height() - camera.cy()) / camera.fy()};
  c.map.published_worked_mask = rc.worked_mask_scalar;
  c.map.published_early_return = rc.early_return_stale;
  c.map.published_dbof_on_ovde_pf = rc.dbof_on_ovde_polyhedron;
  c.map.published_ovde_activation = rc.ovde_parallax_frames;
  c.map.published_dbof_pinhole = rc.dbof_pinhole_projection;
  if (rc.plain_pose_blocking) c.planner.viewpoints.frontier_view_limit = 0;
  return c;
}
}  // namespace

MonoSpheresExplorer::MonoSpheresExplorer(const MonoSpheresConfig& config, const FisheyeCamera& camera,
                                         const ExplorerContext& context)
    : config_(withSharedKeys(checkValid(config), camera)),
      context_(context),
      map_(config_.map, camera, context.seed),
      clearance_(map_, config_.planner, config_.planner.clearance),
      repair_(map_, config_.planner.repair, config_.planner.safety, config_.planner,
              config_.planner.goals.no_progress_timeout_s),
      viewpoints_(config_.planner.viewpoints, context.seed),
      goals_(config_.planner.goals, config_.reference_code, viewpoints_, map_,
             [this](const Vec3& from, const SpherePath& path, const Vec3& goal) { return routeTo(from, path, goal); }),
      takeoff_(context.start, config.planner) {}

MonoSpheresExplorer::~MonoSpheresExplorer() = default;

void MonoSpheresExplorer::observe(const SlamPointsFrame& frame) {
  const MapUpdateStats st = map_.update(frame);
  if (st.graph_stale) ++counters_[MonoSpheresCounter::kMapUpdatesGraphStale];
  if (st.returned_early) ++counters_[MonoSpheresCounter::kMapUpdatesReturnedEarly];
  ++map_updates_since_plan_;
}

PathCommand MonoSpheresExplorer::command(const VehicleState& s, std::vector<Waypoint> w) {
  last_send_s_ = s.t_s;
  return sendPath(s, std::move(w), last_path_, counters_[MonoSpheresCounter::kPathsSent]);
}

std::optional<PathCommand> MonoSpheresExplorer::plan(const VehicleState& s) {
  return takeOffThenExplore(
      takeoff_, s, [&](std::vector<Waypoint> w) { return command(s, std::move(w)); }, [&] { return publishedStep(s); });
}

std::optional<PathCommand> MonoSpheresExplorer::publishedStep(const VehicleState& s) {
  // The published planning tick (OVX planning_loop_iter): the stop check first, then the slow
  // planning, gated on two map updates since its last run. Both off: the intended step.
  const ReferenceCodeConfig& rc = config_.reference_code;
  if (rc.hardstop_drops_goal)
    if (auto stop = publishedHardStop(s)) return stop;
  if (rc.planning_gate_two_updates) {
    if (map_updates_since_plan_ < 2) {
      ++counters_[MonoSpheresCounter::kPlanningStepsGated];
      return std::nullopt;
    }
    map_updates_since_plan_ = 0;
  }
  return explore(s);
}

std::optional<PathCommand> MonoSpheresExplorer::publishedHardStop(const VehicleState& s) {
  // The path still ahead: the last path sent, from the point of it nearest to the vehicle on.
  // (The published code checks the MPC's predicted trajectory; the tracker flies this path.)
  if (!goals_.goal() || last_path_.size() < 2) return std::nullopt;
  const Vec3 p = s.T_W_B.translation();
  size_t seg = 0;
  double best = 1e18, best_t = 0;
  for (size_t i = 0; i + 1 < last_path_.size(); ++i) {
    const Vec3 a = last_path_[i], d = last_path_[i + 1] - a;
    const double t = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    if (const double e = (a + t * d - p).norm(); e < best) best = e, seg = i, best_t = t;
  }
  // Samples 0.25 m apart: unsafe if within the trigger distance of an obstacle point, beyond the
  // clearing distance and within the reach from the vehicle.
  Vec3 a = last_path_[seg] + best_t * (last_path_[seg + 1] - last_path_[seg]);
  for (size_t i = seg + 1; i < last_path_.size(); ++i) {
    const Vec3 b = last_path_[i];
    const double len = (b - a).norm();
    for (double t = 0.25; t <= len; t += 0.25) {
      const Vec3 x = a + t / len * (b - a);
      const double from_vehicle = (x - p).norm();
      if (from_vehicle > kPublishedStopReachM) return std::nullopt;
      if (from_vehicle > kPublishedStopClearingM && map_.anyObstacleNear(x, kPublishedStopTriggerM)) {
        ++counters_[MonoSpheresCounter::kHardStops];
        goals_.drop();
        last_route_send_s_ = s.t_s;  // the one-point path restarts the published re-send timer
        return command(s, {{s.reference.position_m, std::nullopt}});
      }
    }
    a = b;
  }
  return std::nullopt;
}

bool MonoSpheresExplorer::segmentFree(const Vec3& a, const Vec3& b) const {
  // Every sample deep inside a sphere and clear of obstacle points.
  return everySample(a, b, 0.3, [&](const Vec3& x) {
    return !map_.spheresNear(x, -config_.planner.shortcut_depth_m).empty() &&
           !map_.anyObstacleNear(x, config_.planner.check_clearance_m);
  });
}

std::vector<Vec3> MonoSpheresExplorer::routeTo(const Vec3& from, const SpherePath& path, const Vec3& goal) const {
  // From the vehicle (not a waypoint) through the centres to the goal, shortcut; the published
  // path is the raw centres, its first waypoint the start sphere's centre (raw_sphere_paths).
  std::vector<Vec3> pts = {from};
  for (uint64_t id : path.spheres) pts.push_back(map_.spheres().at(id).centre);
  if ((pts.back() - goal).norm() > 1e-6) pts.push_back(goal);
  if (config_.reference_code.raw_sphere_paths) return pts;
  return shortcutPath(pts, [this](const Vec3& a, const Vec3& b) { return segmentFree(a, b); });
}

const SphereLinks* MonoSpheresExplorer::graphLinks(bool relink) {
  if (config_.reference_code.graph_without_links) return nullptr;
  return relink ? &repair_.relink() : &repair_.links();
}

void MonoSpheresExplorer::failGoal(double t_s, MonoSpheresCounter reason) {
  goals_.fail(t_s);
  countFailed(reason);
}

void MonoSpheresExplorer::countFailed(MonoSpheresCounter reason) {
  ++counters_[MonoSpheresCounter::kGoalsFailed];
  ++counters_[reason];
}

std::optional<PathCommand> MonoSpheresExplorer::explore(const VehicleState& s) {
  const auto& pc = config_.planner;
  const Vec3 p = s.T_W_B.translation();
  repair_.beginStep(p, s.t_s);
  // 1. Where the vehicle is in the graph (on a link: its far sphere); links between the parts
  //    of the graph; costs to everything reachable.
  auto start = containingSphere(map_, p, pc.start_max_outside_m, pc.safety.r_min_m);
  if (!start && goals_.goal()) start = repair_.transitStart(s.t_s, goals_.lastProgress());
  if (!start) return returnToFreeSpace(s);
  const SphereCostField field = sphereCostsFrom(map_, *start, pc.safety, repair_.passable(), graphLinks(true));
  std::vector<uint64_t>& reachable = reachable_;
  reachable.clear();
  reachable.reserve(field.cost.size());
  for (const auto& [id, c] : field.cost) reachable.push_back(id);  // ascending ids
  counters_[MonoSpheresCounter::kReachableSpheres] = double(reachable.size());
  // 2. Viewpoints; 3. the active goal; 4. a new goal.
  updateViewpoints(s, reachable);
  checkActiveGoal(s, field);
  if (!goals_.goal()) takeNewGoal(s, field);
  if (goals_.goal())
    no_goal_since_s_ = -1.0;
  else if (no_goal_since_s_ < 0)
    no_goal_since_s_ = s.t_s;
  // 5. Without a goal: bridge out of the vehicle's part of the graph, or look around.
  if (!goals_.goal()) return withoutGoal(s, field, reachable);
  // 6. Fly the route to the goal.
  return followGoal(s, *start);
}

std::optional<PathCommand> MonoSpheresExplorer::returnToFreeSpace(const VehicleState& s) {
  // Outside the known free space: return to the deepest sphere within return_range_m whose
  // centre can be reached along a segment whose samples keep the clearance (tooClose); if none
  // can, stop where the vehicle is.
  const auto& pc = config_.planner;
  if (s.t_s - last_send_s_ < pc.replan_period_s) return std::nullopt;
  const Vec3 p = s.T_W_B.translation();
  std::vector<std::pair<double, uint64_t>> candidates;  // (distance outside, id): deepest first, ties by id
  for (uint64_t id : map_.spheresNear(p, pc.return_range_m)) {
    const Sphere& sp = map_.spheres().at(id);
    if (sp.radius >= pc.safety.r_min_m) candidates.emplace_back((sp.centre - p).norm() - sp.radius, id);
  }
  if (candidates.empty()) return std::nullopt;  // nothing to return to (e.g. an empty map)
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [neg_depth, id] : candidates) {
    const Vec3& c = map_.spheres().at(id).centre;
    if (!clearance_.segmentClear(p, c, p)) continue;
    ++counters_[MonoSpheresCounter::kReturnsToFreeSpace];
    return command(s, {{c, std::nullopt}});
  }
  ++counters_[MonoSpheresCounter::kReturnsRefused];
  return command(s, {{s.reference.position_m, std::nullopt}});
}

void MonoSpheresExplorer::updateViewpoints(const VehicleState& s, const std::vector<uint64_t>& reachable) {
  const auto& pc = config_.planner;
  const Aabb& box = context_.exploration_box;
  // Nothing above the usual value for a while: accept viewpoints that see a few frontiers.
  const bool relaxed = !config_.reference_code.hover_without_goal && !goals_.goal() && no_goal_since_s_ >= 0 &&
                       s.t_s - no_goal_since_s_ >= pc.bridge_after_idle_s && viewpoints_.viewpoints().empty();
  if (relaxed) ++counters_[MonoSpheresCounter::kRelaxedSteps];
  viewpoints_.update(
      map_, reachable, s.T_W_B.translation(), yawOf(s.T_W_B.linear()), s.t_s, goals_.goal(),
      [&box](const Vec3& x) { return box.contains(x); }, relaxed);
}

void MonoSpheresExplorer::checkActiveGoal(const VehicleState& s, const SphereCostField& field) {
  // The active goal's end, counted.
  switch (goals_.checkActive(s, field)) {
    case GoalEnd::kReached:
      ++counters_[MonoSpheresCounter::kGoalsReached];
      break;
    case GoalEnd::kUnreachable:
      countFailed(MonoSpheresCounter::kGoalsFailedUnreachable);
      break;
    case GoalEnd::kNoProgress:
      countFailed(MonoSpheresCounter::kGoalsFailedNoProgress);
      break;
    case GoalEnd::kBlocked:
      countFailed(MonoSpheresCounter::kGoalsFailedBlocked);
      break;
    case GoalEnd::kNone:
    case GoalEnd::kGone:
      break;
  }
}

void MonoSpheresExplorer::takeNewGoal(const VehicleState& s, const SphereCostField& field) {
  bool global = false;
  if (!goals_.takeNew(s, field, &global)) return;
  ++counters_[MonoSpheresCounter::kGoalsChosen];
  if (global) ++counters_[MonoSpheresCounter::kGoalsGlobal];
}

std::optional<PathCommand> MonoSpheresExplorer::withoutGoal(const VehicleState& s, const SphereCostField& field,
                                                            const std::vector<uint64_t>& reachable) {
  const auto& pc = config_.planner;
  if (config_.reference_code.hover_without_goal) return std::nullopt;  // the published vehicle hovers
  const Vec3 p = s.T_W_B.translation();
  const bool stuck_without_goals = s.t_s - no_goal_since_s_ >= pc.bridge_after_idle_s;
  if ((reachable.size() < size_t(pc.bridge_below_reachable) || stuck_without_goals) &&
      s.t_s - last_send_s_ >= pc.replan_period_s) {
    // Cut off in a small pocket of the graph (spheres shrunk or deleted around the vehicle), or
    // nothing left to see in the vehicle's part of the graph: bridge to the nearest sphere
    // outside it along a straight segment clear of obstacle points.
    std::optional<std::pair<double, uint64_t>> best;
    for (uint64_t id : map_.spheresNear(p, pc.bridge_range_m)) {
      const Sphere& sp = map_.spheres().at(id);
      if (field.cost.count(id) || sp.radius < pc.safety.r_min_m || !context_.exploration_box.contains(sp.centre))
        continue;
      const double d = (sp.centre - p).norm();
      if (d > pc.bridge_range_m || (best && d >= best->first)) continue;
      if (clearance_.segmentClear(p, sp.centre, p)) best = {d, id};
    }
    if (best) {
      ++counters_[MonoSpheresCounter::kBridges];
      return command(s, {{map_.spheres().at(best->second).centre, std::nullopt}});
    }
  }
  // Nothing worth flying to: look around in place now and then.
  if (s.t_s - last_idle_turn_s_ >= pc.idle_turn_period_s && pc.idle_turn_deg > 0) {
    last_idle_turn_s_ = s.t_s;
    ++counters_[MonoSpheresCounter::kIdleTurns];
    return command(s, {{s.reference.position_m, wrapAngle(s.reference.yaw_rad + pc.idle_turn_deg * kDeg)}});
  }
  return std::nullopt;
}

std::optional<PathCommand> MonoSpheresExplorer::followGoal(const VehicleState& s, uint64_t start) {
  // Route to the goal through edges that keep the clearance from obstacle points (an edge
  // found too close is blocked for a while and the search repeated), then progress, the
  // predicted-trajectory check, headings and the carrot.
  const auto& pc = config_.planner;
  const Vec3 p = s.T_W_B.translation();
  const double yaw = yawOf(s.T_W_B.linear());
  const Viewpoint& v = viewpoints_.viewpoints().at(goals_.goal());
  std::optional<SpherePath> spath;
  for (int attempt = 0; attempt < pc.max_route_repairs; ++attempt) {
    spath = findSpherePath(map_, start, v.sphere, pc.safety, repair_.passable(), graphLinks(false));
    if (!spath) break;
    bool clear = true;
    for (size_t k = 1; k < spath->spheres.size() && clear && !config_.reference_code.route_edges_unchecked; ++k) {
      const uint64_t a = spath->spheres[k - 1], b = spath->spheres[k];
      if (clearance_.segmentClear(map_.spheres().at(a).centre, map_.spheres().at(b).centre, p)) continue;
      repair_.blockEdge(a, b, s.t_s);
      ++counters_[MonoSpheresCounter::kEdgesBlocked];
      clear = false;
    }
    if (clear) break;
    spath.reset();
  }
  if (!spath && config_.reference_code.failure_counter_never_reset && ++failed_searches_ <= kPublishedSearchTries) {
    // The published code keeps the goal and sends nothing; the next step searches again.
    ++counters_[MonoSpheresCounter::kSearchRetries];
    return std::nullopt;
  }
  if (!spath) {
    failGoal(s.t_s, MonoSpheresCounter::kGoalsFailedUnreachable);
    return command(s, {{s.reference.position_m, std::nullopt}});  // hold; choose again next step
  }
  // A route over a link: its far sphere is where the search starts while crossing the gap.
  if (repair_.noteRoute(*spath, s.t_s)) ++counters_[MonoSpheresCounter::kLinksUsed];
  const std::vector<Vec3> route = routeTo(s.reference.position_m, *spath, v.position);
  const double remaining = pathLength(route);
  goals_.noteRemaining(remaining, s.t_s);
  // The published code has no blocked-route hold: its stop is publishedHardStop.
  if (!config_.reference_code.hardstop_drops_goal && clearance_.pathBlocked(route)) {
    // Already inside an obstacle point's clearance (the point appeared after the vehicle got
    // there): every route that starts even slightly towards it is blocked, so holding here
    // would fail goal after goal. Back away from the points instead and re-plan from there.
    if (auto away = clearance_.escape(s.reference.position_m)) {
      ++counters_[MonoSpheresCounter::kClearanceEscapes];
      goals_.noteUnblocked();
      return command(s, {{*away, std::nullopt}});
    }
    ++counters_[MonoSpheresCounter::kBlockedStops];
    if (goals_.noteBlocked(s.t_s)) countFailed(MonoSpheresCounter::kGoalsFailedBlocked);
    return command(s, {{s.reference.position_m, std::nullopt}});  // stop; re-plan next step
  }
  goals_.noteUnblocked();
  if (!resendDue(s.t_s)) return std::nullopt;
  // The published path's first heading is its first segment's, from the start sphere's centre.
  const size_t first = config_.reference_code.raw_sphere_paths && route.size() >= 3 ? 1 : 0;
  if (pc.goals.fff && route.size() >= 2) {
    const Vec3 d = route[first + 1] - route[first];
    const double dir = std::atan2(d.y(), d.x());
    if (std::hypot(d.x(), d.y()) > 0.5 && std::abs(wrapAngle(dir - yaw)) > pc.align_before_route_deg * kDeg)
      return command(s, {{s.reference.position_m, dir}});  // face the route before flying it
  }
  const HeadingPlan hp =
      assignHeadings(route, v.yaw_rad, pc.goals.fff, pc.goals.fff_turn_rate_rad_per_m, 1.0, s.reference.yaw_rad);
  last_route_send_s_ = s.t_s;
  return command(s, cutAt(route.front(), hp.waypoints, pc.carrot_distance_m));
}

bool MonoSpheresExplorer::resendDue(double t_s) const {
  // The intended re-send every replan period; the published code's (LNM roadmap_following_iter):
  // a path only when none was sent or kPublishedResendS have passed since the last one.
  if (!config_.reference_code.path_resend_8s) return t_s - last_send_s_ >= config_.planner.replan_period_s;
  return t_s - last_route_send_s_ >= kPublishedResendS;
}

std::vector<FreeSpaceElement> MonoSpheresExplorer::freeSpace() const {
  std::vector<FreeSpaceElement> out;
  out.reserve(map_.spheres().size());
  for (const auto& [id, sp] : map_.spheres())
    out.push_back({id, sp.centre, sp.radius, FreeSpaceElement::Footprint::kDisk});
  return out;
}

ExplorerSnapshot sphereMapSnapshot(const SphereMap& map) {
  ExplorerSnapshot snap;
  for (const auto& [id, sp] : map.spheres())
    snap.free_space.push_back({id, sp.centre, sp.radius, FreeSpaceElement::Footprint::kDisk});
  for (const auto& [id, o] : map.obstacles()) snap.obstacles.push_back(o.position);
  for (const auto& [id, f] : map.frontiers()) snap.frontiers.push_back(f.position);
  return snap;
}

ExplorerSnapshot MonoSpheresExplorer::snapshot() const {
  ExplorerSnapshot snap = sphereMapSnapshot(map_);
  for (const auto& [id, v] : viewpoints_.viewpoints()) snap.viewpoints.push_back({v.position, v.yaw_rad});
  for (const auto& m : viewpoints_.markers()) snap.visited.push_back({m.position, m.yaw_rad});
  if (goals_.goal()) {
    const Viewpoint& v = viewpoints_.viewpoints().at(goals_.goal());
    snap.goal = ExplorerSnapshot::Pose2{v.position, v.yaw_rad};
  }
  snap.path = last_path_;
  return snap;
}

Counters<MonoSpheresCounter> MonoSpheresExplorer::sizeCounters() const {
  using C = MonoSpheresCounter;
  Counters<C> c = counters_;
  c[C::kSpheres] = double(map_.spheres().size());
  c[C::kObstaclePoints] = double(map_.obstacles().size());
  c[C::kFrontiers] = double(map_.frontiers().size());
  c[C::kViewpoints] = double(viewpoints_.viewpoints().size());
  return c;
}

std::map<std::string, double> MonoSpheresExplorer::workCounters() const { return sizeCounters().toMap(); }

std::map<std::string, double> MonoSpheresExplorer::counters() const {
  using C = MonoSpheresCounter;
  Counters<C> c = sizeCounters();
  c[C::kVisitedMarkers] = double(viewpoints_.markers().size());
  c[C::kViewpointsPassed] = double(viewpoints_.passedCount());
  c[C::kFrontiersRetired] = double(viewpoints_.retiredFrontiers(map_));
  const CandidateRejections& r = viewpoints_.rejections();
  c[C::kCandidatesOutsideBox] = double(r.outside);
  c[C::kCandidatesVisited] = double(r.visited);
  c[C::kCandidatesBlocked] = double(r.blocked);
  c[C::kCandidatesNoFrontier] = double(r.no_frontier);
  c[C::kCandidatesLowValue] = double(r.low_value);
  c[C::kCandidatesDominated] = double(r.dominated);
  for (const auto& [id, list] : repair_.links()) c[C::kLinks] += 0.5 * double(list.size());
  // Frontiers in the shell of a sphere the vehicle could reach at the last planning step.
  for (const auto& [id, f] : map_.frontiers())
    for (uint64_t sp : map_.spheresNear(f.position, config_.map.shell_max_m))
      if (std::binary_search(reachable_.begin(), reachable_.end(), sp)) {
        ++c[C::kFrontiersReachable];
        break;
      }
  return c.toMap();
}

}  // namespace msb
