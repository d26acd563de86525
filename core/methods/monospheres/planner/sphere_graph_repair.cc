#include "core/methods/monospheres/planner/sphere_graph_repair.h"

#include <algorithm>
#include <set>
#include <tuple>

#include "core/methods/monospheres/planner/clearance_guard.h"

namespace msb {

void SphereGraphRepair::beginStep(const Vec3& p, double t_s) {
  if (trail_.empty() || (p - trail_.back()).norm() >= config_.trail_spacing_m) trail_.push_back(p);
  std::erase_if(blocked_edges_, [&](const auto& e) { return t_s >= e.second; });
}

EdgeFilter SphereGraphRepair::passable() const {
  return [this](uint64_t a, uint64_t b) { return !blocked_edges_.count({std::min(a, b), std::max(a, b)}); };
}

void SphereGraphRepair::blockEdge(uint64_t a, uint64_t b, double t_s) {
  blocked_edges_[{std::min(a, b), std::max(a, b)}] = t_s + config_.blocked_edge_timeout_s;
}

const SphereLinks& SphereGraphRepair::relink() {
  links_ = linkParts();
  return links_;
}

std::optional<uint64_t> SphereGraphRepair::transitStart(double t_s, double last_progress_s) {
  if (t_s >= transit_until_s_ || !map_.spheres().count(transit_sphere_)) return std::nullopt;
  transit_until_s_ = std::max(transit_until_s_, last_progress_s + transit_timeout_s_);
  return transit_sphere_;
}

bool SphereGraphRepair::noteRoute(const SpherePath& path, double t_s) {
  // The first step of the route between spheres that are not neighbours is a link.
  for (size_t k = 1; k < path.spheres.size(); ++k) {
    const uint64_t a = path.spheres[k - 1], b = path.spheres[k];
    if (map_.neighbours(a).count(b)) continue;
    const bool fresh = transit_sphere_ != b || t_s >= transit_until_s_;
    transit_sphere_ = b;
    transit_until_s_ = t_s + transit_timeout_s_;
    return fresh;
  }
  return false;
}

bool SphereGraphRepair::keepsClearance(const Vec3& a, const Vec3& b) const {
  return everySample(a, b, 0.3, [&](const Vec3& x) { return !map_.anyObstacleNear(x, check_.check_clearance_m); });
}

bool SphereGraphRepair::nearTrail(const Vec3& x, size_t from, size_t to) const {
  const double r2 = config_.link_trail_radius_m * config_.link_trail_radius_m;
  for (size_t k = from; k <= to && k < trail_.size(); ++k)
    if ((trail_[k] - x).squaredNorm() <= r2) return true;
  return false;
}

SphereLinks SphereGraphRepair::linkParts() const {
  const GraphRepairConfig& pc = config_;
  const auto part = sphereGraphParts(map_, safety_, passable());
  SphereLinks links;
  std::set<uint64_t> labels;
  for (const auto& [id, label] : part) labels.insert(label);
  if (labels.size() < 2 || pc.link_tests_per_pair == 0) return links;
  // Candidates per pair of parts: (centre distance, sphere a, sphere b, trail range or none).
  struct Candidate {
    double d;
    uint64_t a, b;
    size_t from, to;  // trail indices (from > to: a gap link, no trail)
    bool operator<(const Candidate& o) const { return std::tie(d, a, b, from) < std::tie(o.d, o.a, o.b, o.from); }
  };
  std::map<std::pair<uint64_t, uint64_t>, std::vector<Candidate>> candidates;
  auto pairKey = [&](uint64_t a, uint64_t b) {
    return std::make_pair(std::min(part.at(a), part.at(b)), std::max(part.at(a), part.at(b)));
  };
  // (a) Narrow gaps between spheres of different parts. Every pair of parts has a part other
  // than the largest in it, so only the spheres outside the largest part are scanned (usually a
  // few fragments beside one big part); pairs found from both ends are merged below.
  std::map<uint64_t, size_t> part_size;
  for (const auto& [id, label] : part) ++part_size[label];
  uint64_t largest = 0;
  for (const auto& [label, n] : part_size)
    if (!largest || n > part_size.at(largest)) largest = label;
  for (const auto& [a, label] : part) {
    if (label == largest) continue;
    const Sphere& sa = map_.spheres().at(a);
    for (uint64_t b : map_.spheresNear(sa.centre, sa.radius + pc.link_gap_m)) {
      if (!part.count(b) || part.at(b) == label) continue;
      candidates[pairKey(a, b)].push_back(
          {(map_.spheres().at(b).centre - sa.centre).norm(), std::min(a, b), std::max(a, b), 1, 0});
    }
  }
  // (b) Where the vehicle's trail leaves one part and enters another.
  std::optional<std::pair<size_t, uint64_t>> last;  // (trail index, containing sphere)
  for (size_t k = 0; k < trail_.size(); ++k) {
    const auto in = containingSphere(map_, trail_[k], 0.0, safety_.r_min_m);
    if (!in || !part.count(*in)) continue;
    if (last && part.at(last->second) != part.at(*in) &&
        double(k - last->first) * pc.trail_spacing_m <= pc.link_trail_max_m) {
      const uint64_t a = std::min(last->second, *in), b = std::max(last->second, *in);
      candidates[pairKey(a, b)].push_back(
          {(map_.spheres().at(b).centre - map_.spheres().at(a).centre).norm(), a, b, last->first, k});
    }
    last = {k, *in};
  }
  // The shortest acceptable candidate of each pair becomes a link.
  for (auto& [key, list] : candidates) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(
                   list.begin(), list.end(),
                   [](const Candidate& x, const Candidate& y) { return x.a == y.a && x.b == y.b && x.from == y.from; }),
               list.end());
    int tests = 0;
    for (const Candidate& c : list) {
      if (tests++ >= pc.link_tests_per_pair) break;
      const Vec3 &ca = map_.spheres().at(c.a).centre, &cb = map_.spheres().at(c.b).centre;
      if (!keepsClearance(ca, cb)) continue;
      // A trail link: every sample outside the spheres lies near the trail.
      if (c.from <= c.to && !everySample(ca, cb, 0.5, [&](const Vec3& x) {
            return !map_.spheresNear(x, 0.0).empty() || nearTrail(x, c.from, c.to);
          }))
        continue;
      links[c.a].push_back(c.b);
      links[c.b].push_back(c.a);
      break;
    }
  }
  for (auto& [id, list] : links) std::sort(list.begin(), list.end());
  return links;
}

}  // namespace msb
