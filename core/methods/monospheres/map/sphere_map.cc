#include "core/methods/monospheres/map/sphere_map.h"

#include "core/common/wall_time.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <optional>

#include "core/methods/monospheres/map/free_space_polyhedron.h"

namespace msb {

void SphereMapConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(r_max_m > r_min_m, "r_max_m", "must exceed r_min_m");
  c.require(shell_max_m > shell_min_m, "shell_max_m", "must exceed shell_min_m");
}

namespace {
using Clock = WallClock;
constexpr int kSampleAttemptsPerSample = 20;
double nearestDistance(const Vec3& c, const std::vector<Vec3>& pts) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : pts) best = std::min(best, (p - c).squaredNorm());
  return std::sqrt(best);
}
}  // namespace

SphereMap::SphereMap(const SphereMapConfig& config, const FisheyeCamera& camera, uint64_t seed)
    : config_(checkValid(config)), camera_(camera), ovde_(config.ovde_params, camera), seed_(seed), state_(seed) {}

double SphereMap::ruleRadius(const Vec3& c, double r, const FreeSpacePolyhedron& pf,
                             const std::vector<Vec3>& constraints) const {
  double grown = r;
  if (pf.contains(c)) grown = std::max(r, pf.distance(c));
  return std::min({grown, nearestDistance(c, constraints), config_.r_max_m});
}

uint64_t SphereMap::addSphere(const Vec3& centre, double radius) {
  const uint64_t id = state_.next_sphere++;
  state_.spheres[id] = {id, centre, radius};
  markDirty(centre, radius + config_.shell_max_m);
  auto& adj = state_.adjacency[id];
  for (uint64_t j : state_.sphere_grid.near(centre, radius + config_.r_max_m)) {
    const Sphere& s = state_.spheres.at(j);
    if ((s.centre - centre).norm() < s.radius + radius) {
      adj.insert(j);
      state_.adjacency[j].insert(id);
    }
  }
  state_.sphere_grid.insert(id, centre);
  return id;
}

void SphereMap::removeSphere(uint64_t id) {
  markDirty(state_.spheres.at(id).centre, state_.spheres.at(id).radius + config_.shell_max_m);
  for (uint64_t j : state_.adjacency.at(id)) state_.adjacency[j].erase(id);
  state_.adjacency.erase(id);
  state_.sphere_grid.erase(id, state_.spheres.at(id).centre);
  state_.spheres.erase(id);
}

void SphereMap::setRadius(uint64_t id, double r) {
  Sphere& s = state_.spheres.at(id);
  markDirty(s.centre, std::max(s.radius, r) + config_.shell_max_m);
  s.radius = r;
  relink(id);
}

void SphereMap::relink(uint64_t id) {
  // Overlaps may have appeared or vanished.
  const Sphere& s = state_.spheres.at(id);
  const double r = s.radius;
  for (uint64_t j : state_.adjacency.at(id)) state_.adjacency[j].erase(id);
  auto& adj = state_.adjacency[id];
  adj.clear();
  for (uint64_t j : state_.sphere_grid.near(s.centre, r + config_.r_max_m)) {
    if (j == id) continue;
    const Sphere& o = state_.spheres.at(j);
    if ((o.centre - s.centre).norm() < o.radius + r) {
      adj.insert(j);
      state_.adjacency[j].insert(id);
    }
  }
}

bool SphereMap::sparsify(uint64_t id) {
  const Sphere& s = state_.spheres.at(id);
  const std::set<uint64_t>& adj = state_.adjacency.at(id);
  bool redundant = false;
  for (uint64_t j : adj) {
    const Sphere& o = state_.spheres.at(j);
    redundant = redundant || (o.centre - s.centre).norm() < config_.sparsify_factor * 0.5 * (o.radius + s.radius);
  }
  if (!redundant) return false;
  // Connectivity guard: all of i's neighbours must stay connected without i.
  if (adj.size() > 1) {
    std::set<uint64_t> seen = {*adj.begin()};
    std::deque<uint64_t> queue = {*adj.begin()};
    size_t found = 1;
    while (!queue.empty() && found < adj.size()) {
      const uint64_t k = queue.front();
      queue.pop_front();
      for (uint64_t n : state_.adjacency.at(k)) {
        if (n == id || seen.count(n)) continue;
        seen.insert(n);
        queue.push_back(n);
        found += adj.count(n);
      }
    }
    if (found < adj.size()) return false;
  }
  removeSphere(id);
  return true;
}

double SphereMap::frontierObstacleReach() const {
  // frontierNormal() looks at obstacle points within the gap of the frontier and along its
  // line-of-sight segments towards shell spheres: up to shell_max_m + 0.3 m from it, each
  // sample with a tolerance of obstacle_spacing_m.
  return std::max(config_.frontier_obstacle_gap_m, config_.shell_max_m + 0.3 + config_.obstacle_spacing_m);
}

uint64_t SphereMap::addObstacle(const Vec3& p, double d_min) {
  const uint64_t id = state_.next_obstacle++;
  state_.obstacles[id] = {id, p, d_min, state_.flown_m};
  markDirty(p, frontierObstacleReach());
  state_.obstacle_grid.insert(id, p);
  return id;
}

void SphereMap::eraseObstacle(uint64_t id) {
  const Vec3 p = state_.obstacles.at(id).position;
  markDirty(p, frontierObstacleReach());
  state_.obstacle_grid.erase(id, p);
  state_.obstacles.erase(id);
}

bool SphereMap::insertObstacle(const Vec3& p, double d) {
  const double rho = config_.obstacle_spacing_m;
  std::vector<uint64_t> within;
  for (uint64_t j :
       state_.obstacle_grid.select(p, rho, [&](uint64_t, const Vec3& q) { return (q - p).norm() < rho; })) {
    if (state_.obstacles.at(j).d_min <= d) return false;  // an existing point was measured from closer (or as close)
    within.push_back(j);
  }
  for (uint64_t j : within) eraseObstacle(j);  // measured from farther: replaced
  addObstacle(p, d);
  return true;
}

std::vector<uint64_t> SphereMap::spheresNear(const Vec3& p, double reach) const {
  std::vector<uint64_t> out;
  for (uint64_t id : state_.sphere_grid.near(p, reach + config_.r_max_m)) {
    const Sphere& s = state_.spheres.at(id);
    if ((s.centre - p).norm() <= s.radius + reach) out.push_back(id);
  }
  return out;
}

std::vector<uint64_t> SphereMap::obstaclesNear(const Vec3& p, double r) const {
  return state_.obstacle_grid.select(p, r, [&](uint64_t, const Vec3& q) { return (q - p).norm() <= r; });
}

std::vector<uint64_t> SphereMap::frontiersNear(const Vec3& p, double r) const {
  return state_.frontier_grid.select(p, r, [&](uint64_t, const Vec3& q) { return (q - p).norm() <= r; });
}

bool SphereMap::anyObstacleNear(const Vec3& p, double r) const {
  return state_.obstacle_grid.anyNear(p, r, [&](uint64_t, const Vec3& q) { return (q - p).norm() <= r; });
}

bool SphereMap::connected() const {
  if (state_.spheres.empty()) return true;
  std::set<uint64_t> seen = {state_.spheres.begin()->first};
  std::deque<uint64_t> queue = {state_.spheres.begin()->first};
  while (!queue.empty()) {
    const uint64_t k = queue.front();
    queue.pop_front();
    for (uint64_t n : state_.adjacency.at(k))
      if (seen.insert(n).second) queue.push_back(n);
  }
  return seen.size() == state_.spheres.size();
}

MapUpdateStats SphereMap::update(const SlamPointsFrame& frame_in) {
  MapUpdateStats st;
  // Points too uncertain in depth are left out of every step (off unless configured).
  SlamPointsFrame filtered;
  const bool filter = std::any_of(frame_in.points.begin(), frame_in.points.end(),
                                  [&](const SlamPoint& p) { return p.depth_std_m > config_.max_point_depth_std_m; });
  if (filter) {
    filtered = frame_in;
    std::erase_if(filtered.points, [&](const SlamPoint& p) { return p.depth_std_m > config_.max_point_depth_std_m; });
  }
  const SlamPointsFrame& frame = filter ? filtered : frame_in;
  const Vec3 cam = frame.T_W_C.translation();
  if (state_.last_camera) state_.flown_m += (cam - *state_.last_camera).norm();
  state_.last_camera = cam;

  // 1. Input: points in front of the camera.
  const std::vector<Vec3> input = pointsInView(frame);
  st.input_points = int(input.size());
  // The OVDE pose buffer follows every frame, also those skipped below.
  const std::vector<Vec3> virtual_candidates =
      !config_.ovde                       ? std::vector<Vec3>{}
      : config_.published_ovde_activation ? ovde_.updatePublished(frame.T_W_C, state_.ovde_poses, state_.ovde_active)
                                          : ovde_.update(frame.T_W_C, state_.ovde_poses);
  if (st.input_points < config_.min_points) {
    st.skipped = true;
    return st;
  }

  // 2./4. Free-space polyhedron.
  auto t0 = Clock::now();
  const FreeSpacePolyhedron real_pf(input, frame.T_W_C, config_.max_view_angle_deg);
  if (!real_pf.valid()) {
    st.skipped = true;
    return st;
  }
  // 3. OVDE: active virtual points outside the real points' hull extend P_f.
  std::vector<Vec3> extended = input;
  for (const Vec3& v : virtual_candidates)
    if (!real_pf.surfaceRange(v - cam)) extended.push_back(v), ++st.virtual_points;
  std::optional<FreeSpacePolyhedron> ovde_pf;
  if (st.virtual_points > 0) ovde_pf.emplace(extended, frame.T_W_C, config_.max_view_angle_deg);
  const FreeSpacePolyhedron& pf = ovde_pf ? *ovde_pf : real_pf;
  st.polyhedron_ms = msSince(t0);

  // 5.–9. DBOF, spheres (updated, new, sparsified), obstacle points.
  const std::vector<Vec3> constraints = applyDbof(frame, config_.published_dbof_on_ovde_pf ? pf : real_pf, st);
  std::vector<uint64_t> touched;
  updateSpheresNear(pf, constraints, touched, st);
  sampleNewSpheres(frame, pf, constraints, touched, st);
  sparsifyTouched(touched, st);
  // The published early return (SBM 800-804, 869-873): without a new sphere the update ends
  // before the obstacle points and the frontier candidates.
  st.returned_early = config_.published_early_return && st.new_spheres == 0;
  if (!st.returned_early) insertFrameObstacles(frame, st);

  // 10. Frontiers: re-validate the old ones against the new map, then sample new ones.
  t0 = Clock::now();
  st.dropped_frontiers = revalidateDirtyFrontiers();
  if (!st.returned_early) sampleFrontiers(pf, cam, st);
  st.frontiers_ms = msSince(t0);
  std::vector<uint64_t> alive;
  for (uint64_t id : st.changed_spheres)
    if (state_.spheres.count(id)) alive.push_back(id);
  std::sort(alive.begin(), alive.end());
  alive.erase(std::unique(alive.begin(), alive.end()), alive.end());
  st.changed_spheres = alive;
  return st;
}

std::vector<Vec3> SphereMap::pointsInView(const SlamPointsFrame& frame) const {
  const Pose T_C_W = frame.T_W_C.inverse();
  std::vector<Vec3> input;
  const double min_cos = std::cos(config_.max_view_angle_deg * M_PI / 180.0);
  for (const auto& p : frame.points) {
    const Vec3 c = T_C_W * p.p_W;
    if (c.norm() > 1e-6 && c.z() >= min_cos * c.norm()) input.push_back(p.p_W);
  }
  return input;
}

bool SphereMap::pinholeImageInside(const FreeSpacePolyhedron& pf, const Pose& T_W_C, const Vec3& p_C) const {
  // The published test: the point's undistorted pinhole pixel, read as a fisheye pixel (the
  // frame's triangulation is in distorted pixels), must lie in the image of P_f's surface.
  if (p_C.z() <= 0.0) return false;
  const Vec2 px(camera_.fx() * p_C.x() / p_C.z() + camera_.cx(), camera_.fy() * p_C.y() / p_C.z() + camera_.cy());
  return pf.surfaceRange(T_W_C.linear() * camera_.unproject(px)).has_value();
}

std::vector<Vec3> SphereMap::applyDbof(const SlamPointsFrame& frame, const FreeSpacePolyhedron& real_pf,
                                       MapUpdateStats& st) {
  // DBOF: delete points seen again from close enough inside P_f; protect the others. Every
  // point of this frame limits radii, also those outside the triangulation cone (side points
  // 80–90° off-axis or behind the camera): they are obstacles all the same.
  const auto t0 = Clock::now();
  const Vec3 cam = frame.T_W_C.translation();
  const auto [real_lo, real_hi] = real_pf.bounds();
  const double alpha = config_.dbof ? config_.dbof_alpha : 0.0;
  std::vector<Vec3> constraints;
  constraints.reserve(frame.points.size());
  for (const auto& p : frame.points) constraints.push_back(p.p_W);
  const Pose T_C_W = frame.T_W_C.inverse();
  for (uint64_t id : state_.obstacle_grid.inBox(real_lo, real_hi)) {
    const ObstaclePoint& o = state_.obstacles.at(id);
    if (!real_pf.contains(o.position)) continue;
    if (config_.published_dbof_pinhole && !pinholeImageInside(real_pf, frame.T_W_C, T_C_W * o.position)) continue;
    const double d_eff = o.d_min + config_.dbof_age_per_m * (state_.flown_m - o.flown_at_m);
    if ((o.position - cam).norm() < alpha * d_eff) {
      eraseObstacle(id);
      ++st.deleted_obstacles;
      st.dbof_deleted_ids.push_back(id);
    } else {
      constraints.push_back(o.position);
      ++st.protected_obstacles;
    }
  }
  st.dbof_ms = msSince(t0);
  return constraints;
}

void SphereMap::updateSpheresNear(const FreeSpacePolyhedron& pf, const std::vector<Vec3>& constraints,
                                  std::vector<uint64_t>& touched, MapUpdateStats& st) {
  // Spheres near P_f (its bounding box inflated by the largest radius: the worked set) get the
  // rule's radius.
  const auto t0 = Clock::now();
  const auto [lo, hi] = pf.bounds();
  const std::vector<uint64_t> worked =
      state_.sphere_grid.inBox(lo.array() - config_.r_max_m, hi.array() + config_.r_max_m);
  std::vector<double> radii;
  radii.reserve(worked.size());
  for (uint64_t id : worked)
    radii.push_back(ruleRadius(state_.spheres.at(id).centre, state_.spheres.at(id).radius, pf, constraints));
  if (config_.published_worked_mask && publishedStaleGraph(worked, radii, st)) {
    st.spheres_ms = msSince(t0);
    return;
  }
  for (size_t k = 0; k < worked.size(); ++k) {
    const uint64_t id = worked[k];
    const double r = radii[k], old = state_.spheres.at(id).radius;
    if (r == old) {
      // The published code re-links and prunes every worked sphere (edges or spheres it left
      // stale before are put right here); the intended map never leaves them stale.
      if (!config_.published_worked_mask) continue;
      if (old < config_.r_min_m)
        removeSphere(id), ++st.deleted_spheres;
      else
        relink(id);
      continue;
    }
    ++st.updated_spheres;
    if (r < config_.r_min_m) {
      removeSphere(id);
      ++st.deleted_spheres;
    } else {
      if (r > old) st.changed_spheres.push_back(id);
      setRadius(id, r);
      touched.push_back(id);
    }
  }
  st.spheres_ms = msSince(t0);
}

bool SphereMap::publishedStaleGraph(const std::vector<uint64_t>& worked, const std::vector<double>& radii,
                                    MapUpdateStats& st) {
  // SBM 750-756 tests `radii[worked[i]] < min_radius` with i left at the last index of the
  // radius loop: a scalar. True: every worked sphere is taken for "too small" and then dropped
  // from the set, so neither updateConnections nor removeSpheresIfRedundant sees any of them.
  if (worked.empty() || radii.back() >= config_.r_min_m) return false;
  for (size_t k = 0; k < worked.size(); ++k) {
    Sphere& s = state_.spheres.at(worked[k]);
    if (radii[k] == s.radius) continue;
    ++st.updated_spheres;
    markDirty(s.centre, std::max(s.radius, radii[k]) + config_.shell_max_m);
    if (radii[k] > s.radius) st.changed_spheres.push_back(s.id);
    s.radius = radii[k];  // the edges stay as they were
  }
  st.graph_stale = true;
  return true;
}

Vec3 SphereMap::pinholeRay(const Vec2& px) const {
  // The published mapper's back-projection: K⁻¹ (u, v, 1), normalised.
  return Vec3((px.x() - camera_.cx()) / camera_.fx(), (px.y() - camera_.cy()) / camera_.fy(), 1.0).normalized();
}

void SphereMap::sampleNewSpheres(const SlamPointsFrame& frame, const FreeSpacePolyhedron& pf,
                                 const std::vector<Vec3>& constraints, std::vector<uint64_t>& touched,
                                 MapUpdateStats& st) {
  // New spheres sampled along fisheye rays, uniformly in range up to the depth surface.
  // Directions are drawn over the image until `new_sphere_samples` fall inside P_f's cone
  // (rejection sampling, at most kSampleAttemptsPerSample tries per sample), so a narrow view
  // gets as many samples as an open one.
  const auto t0 = Clock::now();
  const Vec3 cam = frame.T_W_C.translation();
  const int max_attempts = kSampleAttemptsPerSample * config_.new_sphere_samples;
  for (int attempt = 0; attempt < max_attempts && st.sphere_samples < config_.new_sphere_samples; ++attempt) {
    const Vec2 px(state_.rng.uniform(0, camera_.width()), state_.rng.uniform(0, camera_.height()));
    const double t_frac = state_.rng.uniform();
    if (!config_.pinhole_sample_rays && !camera_.pixelInFov(px)) continue;
    const Vec3 dir = frame.T_W_C.linear() * (config_.pinhole_sample_rays ? pinholeRay(px) : camera_.unproject(px));
    const auto range = pf.surfaceRange(dir);
    if (!range) continue;
    ++st.sphere_samples;
    const Vec3 c = cam + t_frac * std::min(*range, config_.max_sample_range_m) * dir;
    const double r = ruleRadius(c, 0.0, pf, constraints);
    if (r < config_.r_min_m) continue;
    touched.push_back(addSphere(c, r));
    st.changed_spheres.push_back(touched.back());
    ++st.new_spheres;
  }
  st.sampling_ms = msSince(t0);
}

void SphereMap::sparsifyTouched(std::vector<uint64_t>& touched, MapUpdateStats& st) {
  // The updated and new spheres, smallest first (ties by id).
  const auto t0 = Clock::now();
  std::sort(touched.begin(), touched.end(), [&](uint64_t a, uint64_t b) {
    const double ra = state_.spheres.count(a) ? state_.spheres.at(a).radius : 0,
                 rb = state_.spheres.count(b) ? state_.spheres.at(b).radius : 0;
    return ra != rb ? ra < rb : a < b;
  });
  for (uint64_t id : touched)
    if (state_.spheres.count(id) && sparsify(id)) ++st.sparsified_spheres;
  st.graph_ms = msSince(t0);
}

void SphereMap::insertFrameObstacles(const SlamPointsFrame& frame, MapUpdateStats& st) {
  // The frame's points within range, merged by distance (the closer measurement wins).
  const auto t0 = Clock::now();
  const Vec3 cam = frame.T_W_C.translation();
  for (const auto& p : frame.points) {
    const double d = (p.p_W - cam).norm();
    if (d <= config_.max_point_range_m && insertObstacle(p.p_W, d)) ++st.inserted_obstacles;
  }
  st.obstacles_ms = msSince(t0);
}

}  // namespace msb
