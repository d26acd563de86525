// Star discovery (von Stumberg et al., "Autonomous exploration with a low-cost quadcopter using
// semi-dense monocular SLAM", §IV-B/C; `method.type: star_discovery`; docs/baseline.md), on the
// same OctoMap map and traversability grid as the grid baseline:
//   1. take off like every method, then a look-around: a full turn on the spot;
//   2. a star discovery from the current position: m rays at equal angles, each marched through
//      the traversability grid (known free cells, occupied ones inflated by the planner's
//      clearance; unknown cells are not traversable but not inflated) to its farthest
//      traversable cell, up to max_ray_m, at l heights around the origin; the height with the
//      largest total ray length wins. The vehicle flies every ray out and back
//      with its heading 90° to the motion (lateral motion gives parallax and closes the
//      "indentations" of unknown space next to textureless surfaces);
//   3. a global step: free, traversable cells not in line of sight of any earlier star origin are
//      "interesting"; among `candidates` random cells of the largest 26-connected component of
//      interesting cells, the one allowing the largest star is flown to (grid A*, re-planned
//      every replan_period_s, with the grid baseline's predicted-path check), then step 2 again.
// With no interesting cell left, the next origin is the traversable cell farthest from every
// earlier origin (our addition: the paper's dense semi-dense maps leave interesting cells; a
// sparse map's free space is mostly rays from the camera positions, all in sight of them);
// with none reachable, a star from the current spot if it is not an origin yet, else the
// vehicle holds its position and looks again after retry_period_s.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/common/rng.h"
#include "core/explorer/counters.h"
#include "core/explorer/explorer.h"
#include "core/explorer/takeoff.h"
#include "core/grid/grid_map.h"
#include "core/grid/grid_path_planner.h"

namespace msb {

/// Star discovery settings (the paper's where it gives them).
struct StarDiscoveryConfig : TakeoffConfig, PathCheckConfig {  // take-off and path-check keys
  GridMapConfig map;                                           ///< OctoMap insertion (as the grid baseline)
  /// Traversability and A*: occupied cells inflated by clearance_m; only known free cells are
  /// traversable, unknown ones are not inflated (the paper: "inflation of the occupied voxels").
  GridPlannerConfig planner{.clearance_m = 1.5, .unknown_is_occupied = true, .unknown_clearance_m = 0.0};
  int rays = 8;                        ///< m: rays per star, at equal angles
  int heights = 3;                     ///< l: heights tried around the origin ...
  double height_step_m = 0.5;          ///< ... this far apart
  double max_ray_m = 15.0;             ///< a ray ends here at the latest
  double min_ray_m = 1.0;              ///< shorter rays are not flown
  int candidates = 10;                 ///< random interesting cells compared per global step
  double los_range_m = 30.0;           ///< line of sight from an origin reaches this far
  double look_around_step_deg = 90.0;  ///< the look-around turns in steps of this
  double replan_period_s = 1.0;        ///< transit paths re-planned this often
  double transit_timeout_s = 60.0;     ///< a target not reached by then is given up
  double retry_period_s = 5.0;         ///< with no reachable candidate: hold, look again after this

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("map", s.map);
    v.group("planner", s.planner);
    v.key("rays", s.rays, Limits::range(3, 64));
    v.key("heights", s.heights, Limits::range(1, 9));
    v.key("height_step_m", s.height_step_m, Limits::nonNegative());
    v.key("max_ray_m", s.max_ray_m, Limits::positive());
    v.key("min_ray_m", s.min_ray_m, Limits::nonNegative());
    v.key("candidates", s.candidates, Limits::range(1, 1000));
    v.key("los_range_m", s.los_range_m, Limits::positive());
    v.key("look_around_step_deg", s.look_around_step_deg, Limits::range(10.0, 180.0));
    v.key("replan_period_s", s.replan_period_s, Limits::positive());
    v.key("transit_timeout_s", s.transit_timeout_s, Limits::positive());
    v.key("retry_period_s", s.retry_period_s, Limits::positive());
    PathCheckConfig::fields(s, v);
    TakeoffConfig::fields(s, v);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// One planned star: its origin and the end of every ray kept (in flight order).
struct Star {
  Vec3 origin = Vec3::Zero();
  std::vector<Vec3> ends;
  double size_m = 0.0;  ///< total ray length
};

/// The star from `origin`: for each of the config's heights, rays marched through the planner's
/// traversable cells (inside its box); the height with the largest total length.
Star planStar(const GridPathPlanner& planner, const Vec3& origin, const StarDiscoveryConfig& config);

/// Dense free / blocked state of a box's cells for line-of-sight tests (cells of the map's
/// resolution aligned with the octree): free = known free in the map.
class LineOfSightGrid {
 public:
  /// Samples the map's occupancy at every cell centre of `box`.
  LineOfSightGrid(const GridMap& map, const Aabb& box);
  /// True if the straight segment a -> b crosses only free cells (sampled every half cell).
  bool clear(const Vec3& a, const Vec3& b) const;
  /// True if the cell containing p is known free.
  bool free(const Vec3& p) const;

 private:
  bool cellOf(const Vec3& p, int* i, int* j, int* k) const;
  double res_;
  Vec3 origin_;
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<uint8_t> free_;
};

/// Interesting cells: centres of traversable, known-free cells of `box` not in line of sight
/// (within `range_m`) of any of `origins`, in cell order.
std::vector<Vec3> interestingCells(const GridMap& map, const GridPathPlanner& planner, const Aabb& box,
                                   const std::vector<Vec3>& origins, double range_m);

/// The largest 26-connected component of cells (centres on a grid of `resolution_m`); ties:
/// the one holding the earliest cell.
std::vector<Vec3> largestComponent(const std::vector<Vec3>& cells, double resolution_m);

/// The counters of this method (metrics.json → counters; Counters<StarDiscoveryCounter>).
enum class StarDiscoveryCounter {
  kStars,
  kStarRays,
  kGlobalSteps,
  kFallbackSteps,
  kHolds,
  kInterestingCells,
  kTransitsReached,
  kTransitsFailed,
  kBlockedStops,
  kPathsSent,
  kMapPoints,
  kLeaves,   // the octree's leaves when asked (set by counters())
  kOrigins,  // star origins so far (set by counters())
  kCount
};
/// The JSON names of StarDiscoveryCounter, in its order.
inline constexpr std::array<const char*, size_t(StarDiscoveryCounter::kCount)> kStarDiscoveryCounterNames = {
    "stars",         "star_rays",         "global_steps",     "fallback_steps",
    "holds",         "interesting_cells", "transits_reached", "transits_failed",
    "blocked_stops", "paths_sent",        "map_points",       "leaves",
    "origins"};

/// The star discovery explorer.
class StarDiscoveryExplorer : public Explorer {
 public:
  /// Throws ConfigError.
  StarDiscoveryExplorer(const StarDiscoveryConfig& config, const ExplorerContext& context);
  void observe(const SlamPointsFrame& frame) override;
  std::optional<PathCommand> plan(const VehicleState& vehicle) override;
  ExplorerSnapshot snapshot() const override;
  /// Writes the map as an OctoMap binary into *out (the "octomap_binary" hook).
  void octomapBinary(std::string* out) const { *out = map_.binary(); }
  std::vector<FreeSpaceElement> freeSpace() const override;
  std::map<std::string, double> counters() const override;

 private:
  friend struct StarDiscoveryTestSeam;  // hand-built maps in tests (star_discovery_test_seam.h)
  enum class Phase { kTakeoff, kLookAround, kStar, kGlobal, kTransit, kHold };
  PathCommand command(const VehicleState& s, std::vector<Waypoint> w);
  std::optional<PathCommand> startStar(const VehicleState& s);
  std::optional<PathCommand> chooseNextOrigin(const VehicleState& s);
  bool pathBlocked(const Vec3& from) const;
  void rebuildPlanner();

  // Configuration (fixed for the explorer's life) ...
  const StarDiscoveryConfig config_;
  const ExplorerContext context_;
  // ... and state: the map, the parts over it, the step's memory.
  GridMap map_;
  GridPathPlanner planner_;
  RngStream candidate_rng_;
  TakeoffSequence takeoff_;
  Phase phase_ = Phase::kTakeoff;
  bool map_changed_ = true, sent_ = false;
  std::vector<Vec3> origins_;
  std::optional<Vec3> target_;
  double last_plan_s_ = -1e9, transit_since_s_ = 0, hold_until_s_ = 0;
  std::vector<Vec3> last_path_;
  Counters<StarDiscoveryCounter> counters_{kStarDiscoveryCounterNames};
};

}  // namespace msb
