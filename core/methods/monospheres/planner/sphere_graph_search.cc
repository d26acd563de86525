#include "core/methods/monospheres/planner/sphere_graph_search.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>

namespace msb {

void SafetyCostConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.positive("r_min_m", r_min_m);
  c.require(r_safe_m > r_min_m, "r_safe_m", "must be larger than r_min_m");
}

double narrownessPenalty(double r, const SafetyCostConfig& cfg) {
  const double x = std::clamp((r - cfg.r_min_m) / (cfg.r_safe_m - cfg.r_min_m), 0.0, 1.0);
  if (cfg.inverted) return r > cfg.r_safe_m ? 0.0 : x * x;  // LNM compute_safety_cost
  return (1.0 - x) * (1.0 - x);
}

double edgeCost(double length_m, double r_to_m, const SafetyCostConfig& cfg) {
  return length_m * (1.0 + cfg.weight * narrownessPenalty(r_to_m, cfg));
}

std::optional<uint64_t> containingSphere(const SphereMap& map, const Vec3& p, double max_outside_m,
                                         double min_radius_m) {
  std::optional<uint64_t> best;
  double best_depth = -max_outside_m;
  for (uint64_t id : map.spheresNear(p, max_outside_m)) {  // ascending ids: ties keep the oldest
    const Sphere& s = map.spheres().at(id);
    if (s.radius < min_radius_m) continue;
    const double depth = s.radius - (s.centre - p).norm();
    if (depth >= best_depth && (!best || depth > best_depth)) best = id, best_depth = depth;
  }
  return best;
}

namespace {

// Search core shared by A* (heuristic towards `goal`) and Dijkstra (goal = 0, no heuristic).
// Ties in the queue are broken by sphere id, so the result never depends on memory layout.
SphereCostField search(const SphereMap& map, uint64_t start, uint64_t goal, const SafetyCostConfig& cfg,
                       const EdgeFilter& passable, const SphereLinks* links) {
  static const std::vector<uint64_t> kNone;
  SphereCostField f;
  const auto& spheres = map.spheres();
  if (!spheres.count(start)) return f;
  const Vec3 goal_c = goal ? spheres.at(goal).centre : Vec3::Zero();
  auto h = [&](uint64_t id) { return goal ? (spheres.at(id).centre - goal_c).norm() : 0.0; };
  using Entry = std::tuple<double, uint64_t>;  // (cost + heuristic, id)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  std::map<uint64_t, bool> closed;
  f.cost[start] = 0.0;
  f.length_m[start] = 0.0;
  open.emplace(h(start), start);
  while (!open.empty()) {
    const auto [prio, id] = open.top();
    open.pop();
    if (closed[id]) continue;
    closed[id] = true;
    if (id == goal) break;
    const Sphere& s = spheres.at(id);
    const auto linked = links ? links->find(id) : SphereLinks::const_iterator{};
    const std::vector<uint64_t>& extra = links && linked != links->end() ? linked->second : kNone;
    auto relax = [&](uint64_t n, bool is_link) {
      const auto t_it = spheres.find(n);
      if (t_it == spheres.end()) return;
      const Sphere& t = t_it->second;
      if (t.radius < cfg.r_min_m || closed[n]) return;
      if (passable && !passable(id, n)) return;
      const double len = (t.centre - s.centre).norm();
      const double c = f.cost[id] + edgeCost(len, is_link ? cfg.r_min_m : t.radius, cfg);
      const auto it = f.cost.find(n);
      if (it != f.cost.end() && it->second <= c) return;
      f.cost[n] = c;
      f.length_m[n] = f.length_m[id] + len;
      f.parent[n] = id;
      open.emplace(c + h(n), n);
    };
    for (uint64_t n : map.neighbours(id)) relax(n, false);
    for (uint64_t n : extra) relax(n, true);
  }
  return f;
}

}  // namespace

SpherePath SphereCostField::pathTo(uint64_t goal) const {
  SpherePath p;
  if (!cost.count(goal)) return p;
  p.cost = cost.at(goal);
  p.length_m = length_m.at(goal);
  for (uint64_t id = goal;;) {
    p.spheres.push_back(id);
    const auto it = parent.find(id);
    if (it == parent.end()) break;
    id = it->second;
  }
  std::reverse(p.spheres.begin(), p.spheres.end());
  return p;
}

std::optional<SpherePath> findSpherePath(const SphereMap& map, uint64_t start, uint64_t goal,
                                         const SafetyCostConfig& cfg, const EdgeFilter& passable,
                                         const SphereLinks* links) {
  if (!map.spheres().count(goal)) return std::nullopt;
  const SphereCostField f = search(map, start, goal, cfg, passable, links);
  if (!f.cost.count(goal)) return std::nullopt;
  return f.pathTo(goal);
}

SphereCostField sphereCostsFrom(const SphereMap& map, uint64_t start, const SafetyCostConfig& cfg,
                                const EdgeFilter& passable, const SphereLinks* links) {
  return search(map, start, 0, cfg, passable, links);
}

std::map<uint64_t, uint64_t> sphereGraphParts(const SphereMap& map, const SafetyCostConfig& cfg,
                                              const EdgeFilter& passable) {
  // Breadth-first search from each unlabelled sphere in id order: the label is the part's
  // smallest id.
  std::map<uint64_t, uint64_t> part;
  std::vector<uint64_t> queue;
  for (const auto& [id, s] : map.spheres()) {
    if (s.radius < cfg.r_min_m || part.count(id)) continue;
    part[id] = id;
    queue.assign(1, id);
    for (size_t k = 0; k < queue.size(); ++k) {
      const uint64_t a = queue[k];
      for (uint64_t b : map.neighbours(a)) {
        if (part.count(b) || map.spheres().at(b).radius < cfg.r_min_m) continue;
        if (passable && !passable(a, b)) continue;
        part[b] = id;
        queue.push_back(b);
      }
    }
  }
  return part;
}

}  // namespace msb
