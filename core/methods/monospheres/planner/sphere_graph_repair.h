// Sphere-graph repair of the MonoSpheres planner (docs/planner.md): spheres shrink and vanish as
// drifted or new points arrive, splitting the graph into parts and leaving frontiers in other
// parts out of reach. Each step, parts are linked by straight segments between sphere centres
// that keep the clearance from obstacle points and (a) span a gap of at most link_gap_m between
// the two spheres' surfaces, or (b) follow the vehicle's own estimated path (every sample outside
// the spheres within link_trail_radius_m of the trail between the two spheres, at most
// link_trail_max_m of trail): space it has flown through. While crossing a link outside every
// sphere, the search starts at the link's far sphere. Graph edges found too close to obstacle
// points are blocked for blocked_edge_timeout_s. Apart from goal choice and clearance safety.
#pragma once

#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "core/common/types.h"
#include "core/explorer/takeoff.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "core/methods/monospheres/planner/sphere_graph_search.h"

namespace msb {

/// The graph repair's parameters: part of MonoSpheresPlannerConfig (`planner.repair`), their keys
/// flat in `method.planner`.
struct GraphRepairConfig {
  double link_gap_m = 4.0;               ///< parts are linked across gaps up to this wide ...
  double link_trail_radius_m = 2.0;      ///< ... or along the vehicle's path (within this) ...
  double link_trail_max_m = 25.0;        ///< ... over at most this much of it
  double trail_spacing_m = 1.0;          ///< the path is remembered every this far
  int link_tests_per_pair = 4;           ///< candidate links tested per pair of parts
  double blocked_edge_timeout_s = 30.0;  ///< a blocked edge stays blocked this long
};

/// The repair state over a sphere map (read, never changed): the vehicle's trail, blocked edges,
/// this step's links and the link being crossed.
class SphereGraphRepair {
 public:
  /// Beside its own parameters it reads the search's sphere admissibility (`safety`, r_min_m), the
  /// clearance a link keeps from obstacle points (`check`, check_clearance_m) and how long a
  /// link's crossing counts after its route (`transit_timeout_s`: the goal's no-progress timeout).
  SphereGraphRepair(const SphereMap& map, const GraphRepairConfig& config, const SafetyCostConfig& safety,
                    const PathCheckConfig& check, double transit_timeout_s)
      : map_(map), config_(config), safety_(safety), check_(check), transit_timeout_s_(transit_timeout_s) {}

  /// Start of a planning step at `t_s`: remembers `p` on the trail (trail_spacing_m apart) and
  /// unblocks the edges whose time is up.
  void beginStep(const Vec3& p, double t_s);
  /// The graph edges not blocked.
  EdgeFilter passable() const;
  /// Blocks the edge a–b until t_s + blocked_edge_timeout_s.
  void blockEdge(uint64_t a, uint64_t b, double t_s);
  /// Links the parts of the graph (as it is now, blocked edges left out); kept as links().
  const SphereLinks& relink();
  /// This step's links (each listed at both ends, ascending).
  const SphereLinks& links() const { return links_; }
  /// While a link is being crossed (its route at most transit_timeout_s ago, or since the last
  /// progress at `last_progress_s`), its far sphere: where the search starts.
  std::optional<uint64_t> transitStart(double t_s, double last_progress_s);
  /// A route that crosses a link: remembers its far sphere until t_s + transit_timeout_s. True if
  /// it is a link not already being crossed.
  bool noteRoute(const SpherePath& path, double t_s);

 private:
  SphereLinks linkParts() const;
  bool keepsClearance(const Vec3& a, const Vec3& b) const;  // no sample near an obstacle point
  bool nearTrail(const Vec3& x, size_t from, size_t to) const;

  const SphereMap& map_;
  GraphRepairConfig config_;
  SafetyCostConfig safety_;
  PathCheckConfig check_;
  double transit_timeout_s_;
  std::vector<Vec3> trail_;  // estimated vehicle positions, trail_spacing_m apart
  SphereLinks links_;
  uint64_t transit_sphere_ = 0;  // far end of the link being crossed
  double transit_until_s_ = -1.0;
  std::map<std::pair<uint64_t, uint64_t>, double> blocked_edges_;  // (low id, high id) → until
};

}  // namespace msb
