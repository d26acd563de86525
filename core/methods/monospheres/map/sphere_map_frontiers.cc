#include <algorithm>
#include <cmath>

#include "core/methods/monospheres/map/free_space_polyhedron.h"
#include "core/methods/monospheres/map/sphere_map.h"

// Frontier sampling and validation of the sphere map (docs/architecture.md §7 step 10).
namespace msb {

std::optional<Vec3> SphereMap::frontierNormal(const Vec3& x, uint64_t self) const {
  const auto& c = config_;
  // Spacing from other frontiers and from every obstacle point.
  if (state_.obstacle_grid.anyNear(x, c.frontier_obstacle_gap_m,
                                   [&](uint64_t, const Vec3& q) { return (q - x).norm() < c.frontier_obstacle_gap_m; }))
    return std::nullopt;
  if (state_.frontier_grid.anyNear(x, c.frontier_spacing_m, [&](uint64_t j, const Vec3& q) {
        return j != self && (q - x).norm() < c.frontier_spacing_m;
      }))
    return std::nullopt;
  // Outside every sphere, inside the shell of at least one; collect the shell spheres' centres.
  Vec3 sum = Vec3::Zero();
  std::vector<Vec3> dirs;
  for (uint64_t j : state_.sphere_grid.near(x, c.r_max_m + c.shell_max_m)) {
    const Sphere& s = state_.spheres.at(j);
    const double d = (s.centre - x).norm();
    if (d <= s.radius) return std::nullopt;
    if (d >= s.radius + c.shell_min_m && d <= s.radius + c.shell_max_m) {
      const Vec3 dir = (s.centre - x) / d;
      // Line of sight: no obstacle point between x and the sphere (a frontier in the shell of a
      // sphere bounded by a wall would otherwise sit behind that wall). The first
      // frontier_obstacle_gap_m are free by the test above; check on to 0.3 m inside the sphere.
      bool blocked = false;
      for (double t = c.frontier_obstacle_gap_m; t <= d - s.radius + 0.3 && !blocked; t += 0.2) {
        const Vec3 y = x + t * dir;
        blocked = state_.obstacle_grid.anyNear(
            y, c.obstacle_spacing_m, [&](uint64_t, const Vec3& q) { return (q - y).norm() < c.obstacle_spacing_m; });
      }
      if (blocked) continue;
      dirs.push_back(dir);
      sum += dirs.back();
    }
  }
  if (dirs.empty()) return std::nullopt;
  // Free space on one side: the centres lie within a hemisphere around their mean direction.
  const Vec3 mean = sum / double(dirs.size());
  if (mean.norm() < c.frontier_min_balance) return std::nullopt;
  const Vec3 n = mean.normalized();
  for (const auto& d : dirs)
    if (d.dot(n) <= 0.0) return std::nullopt;
  if (n.z() < c.frontier_min_normal_z) return std::nullopt;
  return n;
}

int SphereMap::revalidateFrontiers() {
  std::vector<uint64_t> ids;
  for (const auto& [id, f] : state_.frontiers) ids.push_back(id);
  return revalidate(ids);
}

int SphereMap::revalidateDirtyFrontiers() {
  // Frontiers near a change, deduplicated and in id order.
  std::vector<uint64_t> ids;
  for (const auto& [c, reach] : state_.dirty)
    state_.frontier_grid.forEachNear(c, reach, [&](uint64_t id, const Vec3&) { ids.push_back(id); });
  state_.dirty.clear();
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return revalidate(ids);
}

int SphereMap::revalidate(const std::vector<uint64_t>& ids) {
  std::vector<uint64_t> drop;
  for (uint64_t id : ids) {
    Frontier& f = state_.frontiers.at(id);
    const auto n = frontierNormal(f.position, id);
    if (!n)
      drop.push_back(id);
    else
      f.normal = *n;
  }
  for (uint64_t id : drop) {
    state_.frontier_grid.erase(id, state_.frontiers.at(id).position);
    state_.frontiers.erase(id);
  }
  return int(drop.size());
}

void SphereMap::sampleFrontiers(const FreeSpacePolyhedron& pf, const Vec3& cam, MapUpdateStats& st) {
  const auto& c = config_;
  std::vector<Vec3> candidates;
  // Area-weighted points on P_f's faces, jittered.
  const auto tris = pf.triangles();
  std::vector<double> cumulative;
  double total = 0;
  for (const auto& t : tris) cumulative.push_back(total += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm());
  for (int i = 0; i < c.frontier_surface_samples && total > 0; ++i) {
    const double pick = state_.rng.uniform(0, total);
    const size_t k = std::min(
        tris.size() - 1, size_t(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()));
    double a = state_.rng.uniform(), b = state_.rng.uniform();
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const auto& t = tris[k];
    candidates.push_back(t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]) + c.frontier_jitter_m * state_.rng.normal3());
  }
  // Points in the shells of random spheres within range of the camera.
  std::vector<uint64_t> nearby;
  for (uint64_t j : state_.sphere_grid.near(cam, c.frontier_range_m))
    if ((state_.spheres.at(j).centre - cam).norm() <= c.frontier_range_m) nearby.push_back(j);
  for (int i = 0; i < c.frontier_shell_samples && !nearby.empty(); ++i) {
    const Sphere& s = state_.spheres.at(nearby[state_.rng.uniformInt(nearby.size())]);
    const Vec3 dir = state_.rng.normal3().normalized();
    candidates.push_back(s.centre + (s.radius + state_.rng.uniform(c.shell_min_m, c.shell_max_m)) * dir);
  }
  for (const Vec3& x : candidates) st.new_frontiers += tryAddFrontier(x).has_value();
}

std::optional<uint64_t> SphereMap::tryAddFrontier(const Vec3& x) {
  const auto n = frontierNormal(x);
  if (!n) return std::nullopt;
  const uint64_t id = state_.next_frontier++;
  state_.frontiers[id] = {id, x, *n};
  state_.frontier_grid.insert(id, x);
  return id;
}

}  // namespace msb
