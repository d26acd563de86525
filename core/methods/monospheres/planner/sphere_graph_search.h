// Path search on the sphere graph (docs/architecture.md §8): A* over sphere centres with an admissible
// Euclidean heuristic and the safety-aware edge cost L·(1 + w·u(r_j)),
// u(r) = (1 − min((r − r_min)/(r_safe − r_min), 1))², so paths through narrow spheres cost more
// (fix: the reference code inverted this sign). Also a Dijkstra from one sphere to all, used to
// rank many candidate goals by path cost at once, and the "containing sphere" rule for the start
// and goal of a search.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "core/common/config_fields.h"
#include "core/methods/monospheres/map/sphere_map.h"

namespace msb {

/// Parameters of the safety-aware cost.
struct SafetyCostConfig {
  double weight = 50.0;  ///< w
  /// Radius at which the penalty is largest; smaller spheres unused. Not a key of its own: the
  /// explorer sets it to the map's r_min_m (one quantity, one key: method.map.r_min_m).
  double r_min_m = 1.4;
  double r_safe_m = 8.0;  ///< radius from which there is no penalty
  /// The published code's cost (method.reference_code.safety_cost_inverted; not a key of its
  /// own): u(r) = ((max(r, r_min) − r_min)/(r_safe − r_min))², 0 above r_safe.
  bool inverted = false;

  /// The keys, each once with the values it accepts (r_min_m is the map's).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("weight", s.weight, Limits::nonNegative());
    v.moved("r_min_m", "method.map.r_min_m (the minimum sphere radius)");
    v.key("r_safe_m", s.r_safe_m, Limits::positive());
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The penalty u(r) ∈ [0, 1].
double narrownessPenalty(double radius_m, const SafetyCostConfig& cfg);
/// Cost of entering a sphere of radius r_to over an edge of length L.
double edgeCost(double length_m, double r_to_m, const SafetyCostConfig& cfg);

/// Optional edge filter: false if the edge a→b must not be used (e.g. found blocked).
using EdgeFilter = std::function<bool(uint64_t from, uint64_t to)>;

/// Extra graph edges between spheres that do not overlap (links across gaps of the map, see
/// MonoSpheresExplorer); each edge listed under both ends. A link costs like an edge into the
/// narrowest admissible sphere: edgeCost(L, r_min).
using SphereLinks = std::map<uint64_t, std::vector<uint64_t>>;

/// A path through the sphere graph.
struct SpherePath {
  std::vector<uint64_t> spheres;  ///< from start to goal
  double cost = 0.0;              ///< safety-weighted
  double length_m = 0.0;          ///< Euclidean length through the centres
};

/// The sphere that contains p most deeply (largest r − |p − c|), if that depth is ≥ −max_outside.
std::optional<uint64_t> containingSphere(const SphereMap& map, const Vec3& p, double max_outside_m,
                                         double min_radius_m);

/// A* from start to goal sphere. None if unreachable.
std::optional<SpherePath> findSpherePath(const SphereMap& map, uint64_t start, uint64_t goal,
                                         const SafetyCostConfig& cfg, const EdgeFilter& passable = {},
                                         const SphereLinks* links = nullptr);

/// Dijkstra from start: cost to every reachable sphere (with r ≥ r_min) and its predecessor.
struct SphereCostField {
  std::map<uint64_t, double> cost;
  std::map<uint64_t, double> length_m;
  std::map<uint64_t, uint64_t> parent;  ///< start has none
  /// The path to a reached sphere (start first).
  SpherePath pathTo(uint64_t goal) const;
};
/// Costs from `start` to all spheres reachable from it.
SphereCostField sphereCostsFrom(const SphereMap& map, uint64_t start, const SafetyCostConfig& cfg,
                                const EdgeFilter& passable = {}, const SphereLinks* links = nullptr);

/// Connected parts of the sphere graph over spheres with r ≥ cfg.r_min_m and passable edges:
/// sphere id → part label (the smallest id in the part).
std::map<uint64_t, uint64_t> sphereGraphParts(const SphereMap& map, const SafetyCostConfig& cfg,
                                              const EdgeFilter& passable = {});

}  // namespace msb
