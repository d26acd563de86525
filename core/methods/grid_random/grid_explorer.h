// The grid-based baseline of the paper's Table I (architecture §9, `method.type: grid_random`):
// an OctoMap occupancy grid built from the SLAM points, random goals, and grid A*.
//
// Each planning step (estimate frame):
//   1. take off like every method (climb, short straight stretch);
//   2. every goal_period_s: when idle (no goal, or the last path is done) or after
//      goal_timeout_s on the same goal, draw a new goal uniformly in the square of side
//      goal_square_m around the vehicle intersected with the exploration box, at a height
//      uniform in the box's band (stream `baseline_goals`);
//      (a GoalChooser, the goal-only helper of the Python module, replaces the draw);
//   3. every replan_period_s (and after a stop): A* from the vehicle to the goal keeping
//      clearance_m from occupied cells — to the reachable cell closest to the goal when the
//      goal cannot be reached — sent as waypoints without headings (the camera faces the
//      direction of travel);
//   4. the predicted-path check: if the first check_ahead_m of the path pass within
//      check_clearance_m of an occupied cell, stop and re-plan.
// Coverage: a column is explored once its node lies in the xy footprint of a free leaf (the
// leaf's real size after pruning).
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
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

/// Grid explorer settings (reference values; see docs/deviations.md for the replanning rate).
struct GridExplorerConfig : TakeoffConfig, PathCheckConfig {  // take-off and path-check keys
  GridMapConfig map;                                          ///< OctoMap insertion
  GridPlannerConfig planner;                                  ///< A* and clearance
  double goal_period_s = 1.0;                                 ///< goals are (re)drawn at most this often
  double goal_timeout_s = 20.0;                               ///< a goal is abandoned after this long
  double goal_square_m = 40.0;         ///< side of the square around the vehicle goals are drawn in
  double goal_min_altitude_m = 1.0;    ///< goal heights: the box band clipped to this ...
  double goal_ceiling_margin_m = 0.5;  ///< ... and to this far below the box top
  double replan_period_s = 1.0;        ///< path re-planned this often (reference code: 1 s; paper: 0.2 s)
  double reach_distance_m = 1.0;       ///< a goal this close counts as reached
  /// mrs_octomap_planner's failures (octomap_planner.cpp timerMain, STATE_PLANNING, 916-1090 at
  /// 4c95e24): a path ending within min_path_length_m of its start fails too; a failure sends
  /// nothing (the last trajectory goes on) and the next planning step tries again; two failures
  /// in a row make the planner idle (a new goal at the next goal check); a path to the goal or
  /// a new goal resets the count (a path to the best node short of it does not). false: msbench's rule (a failure stops
  /// the vehicle and asks for a new goal at the next goal check).
  bool reference_failures = false;
  double min_path_length_m = 0.2;  ///< with reference_failures: the reference's `min_path_length`

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("map", s.map);
    v.group("planner", s.planner);
    v.key("goal_period_s", s.goal_period_s, Limits::positive());
    v.key("goal_timeout_s", s.goal_timeout_s, Limits::positive());
    v.key("goal_square_m", s.goal_square_m, Limits::positive());
    v.key("goal_min_altitude_m", s.goal_min_altitude_m, Limits::nonNegative());
    v.key("goal_ceiling_margin_m", s.goal_ceiling_margin_m, Limits::nonNegative());
    v.key("replan_period_s", s.replan_period_s, Limits::positive());
    v.key("reach_distance_m", s.reach_distance_m, Limits::positive());
    v.key("reference_failures", s.reference_failures);
    v.key("min_path_length_m", s.min_path_length_m, Limits::nonNegative());
    PathCheckConfig::fields(s, v);
    TakeoffConfig::fields(s, v);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
  /// The authors' grid session (tmux_scripts/*_octomap_random_explorer of ctu-mrs/monospheres):
  /// mrs_octomap_planner's A* expands only cells the map knows as free (astar_planner.cpp,
  /// getNeighborhood: `tree.search(key)` must exist and be free), and its `unknown_is_occupied:
  /// False` (octomap_planner.yaml) only keeps unknown cells from inflating the clearance — here
  /// unknown cells blocked with no clearance kept from them (unknown_clearance_m 0); and
  /// mrs_octomap_server's map, pruned as it updates; and random_octomap_explorer.py's goal
  /// heights, uniform over the box's whole band (`sample_free_point`: z uniform in
  /// [z_min, z_max] of the safety area), no floor or ceiling margin; and the planner's 0.4 m
  /// planning tree (octomap_planner.yaml `planning_tree/resolution`, not set by the sessions;
  /// results/planning_tree/: it matters); and the planner's one-second budget, its A* rules
  /// and its failure rules (`timeout_threshold: 1.0` of the sessions' octomap_planner.yaml;
  /// results/grid_budget/). Applied by
  /// `method.reference_code: published` before the keys a scenario names (docs/baseline.md, "The
  /// published configuration").
  void applyPublishedSettings() {
    planner.unknown_is_occupied = true;
    planner.unknown_clearance_m = 0.0;
    map.prune = true;
    goal_min_altitude_m = 0.0;
    goal_ceiling_margin_m = 0.0;
    planner.planning_tree_resolution_m = 0.4;
    planner.time_budget_s = 1.0;
    planner.reference_search = true;
    reference_failures = true;
  }
  /// The OctoMap leaf size: the authors' evaluation rule for OctoMap maps (BUG-11) scores the
  /// grid baseline's free cells beside msbench's squares (coverage.area_published_rule_m2).
  double octreeResolutionM() const { return map.resolution_m; }
};

/// What a goal chooser is asked at every goal check (estimate frame).
struct GoalRequest {
  double t_s = 0.0;
  Vec3 position = Vec3::Zero();  ///< the vehicle
  bool needs_goal = true;        ///< the baseline would draw a new goal now (none, reached, idle, timed out)
  const GridMap* map = nullptr;  ///< the explorer's map (valid during the call)
};

/// A goal chooser replacing the random draw (the goal-only helper for Python methods,
/// docs/python.md): nothing keeps the current goal (none if one is needed); an empty list means
/// no goal (hover); one point is a goal A* plans to on the map; more are a path flown as given,
/// its last point the goal (the predicted-path check still stops the vehicle, then A* takes over).
using GoalChooser = std::function<std::optional<std::vector<Vec3>>(const GoalRequest&)>;

/// The counters of this method (metrics.json → counters; Counters<GridCounter>).
enum class GridCounter {
  kGoalsChosen,
  kGoalsReached,
  kGoalsTimedOut,
  kGoalsIdle,
  kPathsSent,
  kPathsToClosestCell,
  kPathsFailed,
  kPathsOverBudget,  // the search stopped by the time budget
  kBlockedStops,
  kMapPoints,
  kLeaves,       // the octree's leaves when asked (set by counters())
  kMapMemoryMb,  // the octree's memory when asked (set by counters())
  kCount
};
/// The JSON names of GridCounter, in its order.
inline constexpr std::array<const char*, size_t(GridCounter::kCount)> kGridCounterNames = {
    "goals_chosen", "goals_reached",     "goals_timed_out", "goals_idle", "paths_sent", "paths_to_closest_cell",
    "paths_failed", "paths_over_budget", "blocked_stops",   "map_points", "leaves",     "map_memory_mb"};

/// The grid explorer.
class GridExplorer : public Explorer {
 public:
  /// Throws ConfigError.
  GridExplorer(const GridExplorerConfig& config, const ExplorerContext& context);

  void observe(const SlamPointsFrame& frame) override;
  std::optional<PathCommand> plan(const VehicleState& vehicle) override;
  ExplorerSnapshot snapshot() const override;
  std::vector<FreeSpaceElement> freeSpace() const override;
  std::map<std::string, double> counters() const override;

  /// The map (tests, tools).
  const GridMap& map() const { return map_; }
  /// Writes the map as an OctoMap binary into *out (the "octomap_binary" hook).
  void octomapBinary(std::string* out) const { *out = map_.binary(); }
  /// The current goal, if any.
  const std::optional<Vec3>& goal() const { return goal_; }
  /// Draws a goal for a vehicle at p (advances the goal stream; tests).
  Vec3 drawGoal(const Vec3& p);
  /// Goals from `chooser` instead of the random draw (asked every goal_period_s).
  void setGoalChooser(GoalChooser chooser) { chooser_ = std::move(chooser); }

 private:
  friend struct GridExplorerTestSeam;  // hand-built maps in tests (grid_test_seam.h)
  std::optional<PathCommand> explore(const VehicleState& s);
  bool checkGoal(const VehicleState& s);
  void setGoal(double t_s, std::optional<Vec3> goal, std::vector<Vec3> path = {});
  std::optional<PathCommand> replan(const VehicleState& s);
  PathCommand command(const VehicleState& s, std::vector<Waypoint> w);
  bool pathBlocked(const Vec3& from) const;
  int expansionBudget(bool moving) const;
  std::optional<PathCommand> planFailed(const VehicleState& s);

  // Configuration (fixed for the explorer's life) ...
  const GridExplorerConfig config_;
  const ExplorerContext context_;
  // ... and state: the map, the parts over it, the step's memory.
  GridMap map_;
  GridPathPlanner planner_;
  RngStream goal_rng_;
  TakeoffSequence takeoff_;
  bool map_changed_ = true;
  std::optional<Vec3> goal_;
  GoalChooser chooser_;
  std::vector<Vec3> given_path_;  // a chooser's path, flown as given (until a stop)
  bool flying_given_ = false;     // that path was sent
  bool path_sent_ = false, replan_now_ = false;
  double goal_since_s_ = 0, last_goal_check_s_ = -1e9, last_plan_s_ = -1e9;
  int failures_ = 0;   // failed plans in a row (reference_failures) ...
  bool idle_ = false;  // ... and the planner idle after too many of them
  std::vector<Vec3> last_path_;
  Counters<GridCounter> counters_{kGridCounterNames};
};

}  // namespace msb
