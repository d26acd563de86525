// The MonoSpheres exploration method (paper §IV, docs/architecture.md §8): the sphere map plus a planner
// that picks frontier viewpoints and flies sphere-graph paths to them.
//
// Each planning step (in the estimate frame):
//   1. start sphere = the sphere containing the vehicle most deeply (≤ 1.5 m outside);
//      Dijkstra with the safety cost gives every reachable sphere's path cost;
//   2. viewpoints: re-valued, VPB applied, 300 new candidates at reachable centres in the box;
//   3. the active goal is reached (1 m, 90°) → removed (+ marker with VPB), or fails after
//      10 s without progress / an unreachable goal / repeated blocking → blacklisted;
//   4. without a goal: the cheapest viewpoint within 15 m (local); after 3 local misses the
//      cheapest anywhere (global); with FFF goals whose turn does not fit are skipped;
//   5. the A* route's edges must keep 1 m from obstacle points (an edge that does not is blocked
//      for 30 s and the search repeated: overlapping spheres can meet in a narrow neck);
//      the route (vehicle → sphere centres → viewpoint) is shortcut inside the sphere union,
//      given headings (FFF or goal heading), cut at the carrot (15 m) and sent every
//      replan period, unless the first 5 m pass closer than 1 m to an obstacle point
//      (then stop and re-plan; if the vehicle itself is inside that 1 m, it first backs away
//      from the points to escape_margin_m beyond it) or FFF first needs a turn in place
//      towards the route.
// Goal choice and the goal's end (steps 3–4): GoalChoice (goal_choice.h). Parts of the graph
// joined by links, edges blocked near obstacle points and the link being crossed:
// SphereGraphRepair (sphere_graph_repair.h). Clearance safety: ClearanceGuard.
// Without a goal while cut off in a small pocket of the graph, or for 5 s without any goal, the
// vehicle bridges straight to the nearest sphere outside its part of the graph within
// bridge_range_m. A bridge may cross space without spheres (that is its purpose) but no sample
// of it may come within check_clearance_m of an obstacle point (with allow_moving_away: unless it
// moves away from a point the vehicle is already closer to). The return to free space (outside
// every sphere) obeys the same rule; if no nearby sphere can be reached that way, the vehicle stops.
// Before exploring: take off vertically and fly a short straight stretch forward, so that the
// first points get parallax.
#pragma once

#include <array>
#include "core/common/config_fields.h"

#include <memory>

#include "core/camera/fisheye_camera.h"
#include "core/explorer/counters.h"
#include "core/explorer/explorer.h"
#include "core/explorer/takeoff.h"
#include "core/methods/monospheres/map/reference_code.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "core/methods/monospheres/planner/clearance_guard.h"
#include "core/methods/monospheres/planner/goal_choice.h"
#include "core/methods/monospheres/planner/path_shaping.h"
#include "core/methods/monospheres/planner/sphere_graph_repair.h"
#include "core/methods/monospheres/planner/sphere_graph_search.h"
#include "core/methods/monospheres/planner/viewpoint_set.h"

namespace msb {

/// Planner parameters (docs/architecture.md §8 defaults).
struct MonoSpheresPlannerConfig : TakeoffConfig, PathCheckConfig {  // take-off and path-check keys
  GoalChoiceConfig goals;                ///< the goal rule (FFF, local and global goals, progress)
  GraphRepairConfig repair;              ///< links across gaps and along the trail, blocked edges
  ClearanceConfig clearance;             ///< the approach rule and the way out of a clearance
  double align_before_route_deg = 90.0;  ///< FFF: turn in place first if the route starts this far off
  ViewpointConfig viewpoints;            ///< sampling, value, VPB
  SafetyCostConfig safety;               ///< A* edge cost
  double start_max_outside_m = 1.5;      ///< start sphere may be this far outside
  double carrot_distance_m = 15.0;       ///< path sent up to this far along the route
  double replan_period_s = 0.4;          ///< how often the path is re-sent
  int max_route_repairs = 8;             ///< searches per step, each blocking one too-close edge
  int bridge_below_reachable = 10;       ///< without a goal and fewer reachable spheres than this ...
  double bridge_range_m = 15.0;          ///< ... fly straight to the nearest other sphere within this range
  double bridge_after_idle_s = 5.0;      ///< ... or after this long without any goal
  double return_range_m = 6.0;           ///< return to free space: spheres this far outside
  double shortcut_depth_m = 0.3;         ///< shortcut samples must lie this deep inside a sphere
  double idle_turn_deg = 90.0;           ///< without goals, turn in place by this much ...
  double idle_turn_period_s = 3.0;       ///< ... this often

  /// The keys, each once with the values it accepts (the switch fff is read under method.switches).
  /// The parts' keys stay flat in `method.planner` (as the paper and the published code's
  /// parameter files name them, and as every committed scenario spells them); each lives in its
  /// part (`goals`, `repair`, `clearance`), the one place it is defaulted.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("viewpoints", s.viewpoints);
    v.group("safety", s.safety);
    v.key("fff_turn_rate_rad_per_m", s.goals.fff_turn_rate_rad_per_m, Limits::positive());
    v.key("align_before_route_deg", s.align_before_route_deg, Limits::range(0.0, 180.0));
    v.key("start_max_outside_m", s.start_max_outside_m, Limits::nonNegative());
    v.key("local_radius_m", s.goals.local_radius_m, Limits::positive());
    v.key("local_misses_before_global", s.goals.local_misses_before_global, Limits::range(0, 1000));
    v.key("max_goal_candidates", s.goals.max_goal_candidates, Limits::range(1, 10000));
    v.key("carrot_distance_m", s.carrot_distance_m, Limits::positive());
    v.key("replan_period_s", s.replan_period_s, Limits::positive());
    PathCheckConfig::fields(s, v);
    v.key("allow_moving_away", s.clearance.allow_moving_away);
    v.key("max_blocked_steps", s.goals.max_blocked_steps, Limits::range(1, 10000));
    v.key("max_route_repairs", s.max_route_repairs, Limits::range(1, 1000));
    v.key("blocked_edge_timeout_s", s.repair.blocked_edge_timeout_s, Limits::positive());
    v.key("escape_margin_m", s.clearance.escape_margin_m, Limits::range(0.0, 5.0));
    v.key("bridge_below_reachable", s.bridge_below_reachable, Limits::range(0, 1000000));
    v.key("bridge_range_m", s.bridge_range_m, Limits::positive());
    v.key("bridge_after_idle_s", s.bridge_after_idle_s, Limits::positive());
    v.key("link_gap_m", s.repair.link_gap_m, Limits::nonNegative());
    v.key("link_trail_radius_m", s.repair.link_trail_radius_m, Limits::nonNegative());
    v.key("link_trail_max_m", s.repair.link_trail_max_m, Limits::nonNegative());
    v.key("trail_spacing_m", s.repair.trail_spacing_m, Limits::positive());
    v.key("link_tests_per_pair", s.repair.link_tests_per_pair, Limits::range(0, 1000));
    v.key("return_range_m", s.return_range_m, Limits::positive());
    v.key("shortcut_depth_m", s.shortcut_depth_m, Limits::nonNegative());
    v.key("reach_distance_m", s.goals.reach_distance_m, Limits::positive());
    v.key("reach_angle_deg", s.goals.reach_angle_deg, Limits::range(0.0, 180.0));
    v.key("no_progress_timeout_s", s.goals.no_progress_timeout_s, Limits::positive());
    TakeoffConfig::fields(s, v);
    v.key("idle_turn_deg", s.idle_turn_deg, Limits::range(0.0, 180.0));
    v.key("idle_turn_period_s", s.idle_turn_period_s, Limits::positive());
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The published code's path re-send period (LNM mrs_path_failing_time), s.
inline constexpr double kPublishedResendS = 8.0;
/// Failed path searches the published code tolerates in a whole mission before a failed search
/// fails its goal (LNM max_goal_vp_pathfinding_times).
inline constexpr int kPublishedSearchTries = 3;
/// The published stop (LNM quick_replanning_iter, local_nav in mrs_sim.yaml): points of the path
/// ahead closer than this to the vehicle are not checked (clearing_dist), m ...
inline constexpr double kPublishedStopClearingM = 1.5;
/// ... a checked point this close to an obstacle point is unsafe (safety_replanning_trigger_odist), m ...
inline constexpr double kPublishedStopTriggerM = 1.0;
/// ... and an unsafe point farther than this from the vehicle does not stop it yet (mindist), m.
inline constexpr double kPublishedStopReachM = 5.0;

/// Mapper + planner configuration of the method.
struct MonoSpheresConfig {
  SphereMapConfig map;
  MonoSpheresPlannerConfig planner;
  ReferenceCodeConfig reference_code;  ///< the published code's defects (all off: the intended method)
  /// The mapper's and the planner's tables (the switches and reference_code are read in tools/config).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("map", s.map);
    v.group("planner", s.planner);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
  /// The paper's four ablation switches (OVDE, DBOF, FFF, VPB) by name, for reports.
  std::map<std::string, bool> switches() const {
    return {{"ovde", map.ovde}, {"dbof", map.dbof}, {"fff", planner.goals.fff}, {"vpb", planner.viewpoints.vpb}};
  }
  /// The published code's switches by name, for the run's record.
  std::map<std::string, bool> referenceCode() const { return reference_code.values(); }
  /// The authors' values where their simulation config (monospheres/config/mrs_sim.yaml of
  /// ctu-mrs/monospheres) differs from msbench's defaults: `min_sphere_rad: 1.6` for map and
  /// planning (msbench 1.4, docs/deviations.md) and `max_heading_change_per_m: 0.314159` (msbench
  /// 0.314). Applied by `method.reference_code: published` before the keys a scenario names, so a
  /// key named beside it wins (docs/deviations.md, "The published configuration").
  void applyPublishedSettings() {
    map.r_min_m = 1.6;
    planner.goals.fff_turn_rate_rad_per_m = 0.314159;
  }
};

/// Spheres, obstacle points and frontiers of a map as a snapshot (drawing, map.ply, hashing).
ExplorerSnapshot sphereMapSnapshot(const SphereMap& map);

/// The counters of this method (metrics.json → counters; Counters<MonoSpheresCounter>).
enum class MonoSpheresCounter {
  kGoalsChosen,
  kGoalsReached,
  kGoalsFailed,
  kGoalsFailedNoProgress,
  kGoalsFailedUnreachable,
  kGoalsFailedBlocked,
  kGoalsGlobal,
  kBlockedStops,
  kPathsSent,
  kIdleTurns,
  kReturnsToFreeSpace,
  kReturnsRefused,
  kEdgesBlocked,
  kBridges,
  kRelaxedSteps,
  kLinksUsed,
  kClearanceEscapes,
  kReachableSpheres,
  kSearchRetries,
  kMapUpdatesGraphStale,
  kMapUpdatesReturnedEarly,
  kPlanningStepsGated,
  kHardStops,
  // The state of the map and the viewpoint set at the time of asking (set by counters()).
  kSpheres,
  kObstaclePoints,
  kFrontiers,
  kViewpoints,
  kVisitedMarkers,
  kViewpointsPassed,
  kFrontiersRetired,
  kCandidatesOutsideBox,
  kCandidatesVisited,
  kCandidatesBlocked,
  kCandidatesNoFrontier,
  kCandidatesLowValue,
  kCandidatesDominated,
  kLinks,
  kFrontiersReachable,
  kCount
};
/// The JSON names of MonoSpheresCounter, in its order.
inline constexpr std::array<const char*, size_t(MonoSpheresCounter::kCount)> kMonoSpheresCounterNames = {
    "goals_chosen",
    "goals_reached",
    "goals_failed",
    "goals_failed_no_progress",
    "goals_failed_unreachable",
    "goals_failed_blocked",
    "goals_global",
    "blocked_stops",
    "paths_sent",
    "idle_turns",
    "returns_to_free_space",
    "returns_refused",
    "edges_blocked",
    "bridges",
    "relaxed_steps",
    "links_used",
    "clearance_escapes",
    "reachable_spheres",
    "search_retries",
    "map_updates_graph_stale",
    "map_updates_returned_early",
    "planning_steps_gated",
    "hard_stops",
    "spheres",
    "obstacle_points",
    "frontiers",
    "viewpoints",
    "visited_markers",
    "viewpoints_passed",
    "frontiers_retired",
    "candidates_outside_box",
    "candidates_visited",
    "candidates_blocked",
    "candidates_no_frontier",
    "candidates_low_value",
    "candidates_dominated",
    "links",
    "frontiers_reachable"};

/// The MonoSpheres explorer.
class MonoSpheresExplorer : public Explorer {
 public:
  /// Throws ConfigError if the config is invalid.
  MonoSpheresExplorer(const MonoSpheresConfig& config, const FisheyeCamera& camera, const ExplorerContext& context);
  ~MonoSpheresExplorer() override;

  void observe(const SlamPointsFrame& frame) override;
  std::optional<PathCommand> plan(const VehicleState& vehicle) override;
  std::vector<FreeSpaceElement> freeSpace() const override;
  ExplorerSnapshot snapshot() const override;
  std::map<std::string, double> counters() const override;
  /// The map's sizes (spheres, obstacle points, frontiers, viewpoints) and the counters kept as
  /// the method runs, without counters()' reachability pass.
  std::map<std::string, double> workCounters() const override;

  /// The map (tests, tools).
  const SphereMap& map() const { return map_; }
  /// The viewpoints (tests, tools).
  const ViewpointSet& viewpoints() const { return viewpoints_; }
  /// The active goal's viewpoint id (0 = none).
  uint64_t goal() const { return goals_.goal(); }
  /// Goals from `chooser` instead of MonoSpheres' rule (asked whenever a new goal is taken).
  void setViewpointChooser(ViewpointChooser chooser) { goals_.setChooser(std::move(chooser)); }

 private:
  friend struct MonoSpheresTestSeam;  // hand-built maps in tests (monospheres_test_seam.h)

  // One exploration step, in the order of the file comment; each step below is one part of it.
  std::optional<PathCommand> explore(const VehicleState& s);
  std::optional<PathCommand> returnToFreeSpace(const VehicleState& s);  // outside every sphere
  void updateViewpoints(const VehicleState& s, const std::vector<uint64_t>& reachable);
  void checkActiveGoal(const VehicleState& s, const SphereCostField& field);  // reached / failed
  void takeNewGoal(const VehicleState& s, const SphereCostField& field);
  void failGoal(double t_s, MonoSpheresCounter reason);  // fail now, counted
  void countFailed(MonoSpheresCounter reason);           // a goal failed for `reason`
  std::optional<PathCommand> withoutGoal(const VehicleState& s, const SphereCostField& field,
                                         const std::vector<uint64_t>& reachable);       // bridge or turn
  std::optional<PathCommand> followGoal(const VehicleState& s, uint64_t start_sphere);  // route, carrot
  std::vector<Vec3> routeTo(const Vec3& from, const SpherePath& path, const Vec3& goal) const;
  const SphereLinks* graphLinks(bool relink);                       // the repair's links (re-found), none if published
  bool segmentFree(const Vec3& a, const Vec3& b) const;             // inside the sphere union and clear
  bool resendDue(double t_s) const;                                 // the route's path may be (re-)sent now
  std::optional<PathCommand> publishedStep(const VehicleState& s);  // gate and stop, then explore
  std::optional<PathCommand> publishedHardStop(const VehicleState& s);  // the published stop check
  PathCommand command(const VehicleState& s, std::vector<Waypoint> w);

  // Configuration (fixed for the explorer's life) ...
  const MonoSpheresConfig config_;
  const ExplorerContext context_;
  // ... and state: the map, the parts over it, the step's memory.
  SphereMap map_;
  ClearanceGuard clearance_;  // clearance safety over map_'s obstacle points
  SphereGraphRepair repair_;  // links between graph parts, blocked edges, the trail
  ViewpointSet viewpoints_;
  GoalChoice goals_;  // the active goal and the rule for the next (over viewpoints_)
  TakeoffSequence takeoff_;
  double last_send_s_ = -1e9, last_idle_turn_s_ = -1e9, no_goal_since_s_ = -1.0;
  double last_route_send_s_ = -1e9;  // the last path to the carrot (the published 8 s timer)
  int failed_searches_ = 0;          // the published mission-wide count (never reset)
  int map_updates_since_plan_ = 0;   // the published planning gate's count
  std::vector<Vec3> last_path_;
  std::vector<uint64_t> reachable_;  // this step's reachable spheres (ascending)
  Counters<MonoSpheresCounter> counters_{kMonoSpheresCounterNames};
  // The counters kept as the method runs, with the map's sizes (workCounters, counters).
  Counters<MonoSpheresCounter> sizeCounters() const;
};

}  // namespace msb
