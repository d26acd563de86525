// Goal choice of the MonoSpheres planner (docs/planner.md): which viewpoint the vehicle flies
// to, and when that goal ends. Apart from the sphere graph (SphereGraphRepair) and clearance
// safety (ClearanceGuard).
//
// A goal ends when it is reached (within reach_distance_m and reach_angle_deg: removed, with a
// VPB marker), when its viewpoint is gone (VPB or re-valuing), or when it fails (unreachable, no
// 0.5 m progress for no_progress_timeout_s, blocked max_blocked_steps steps running: blacklisted).
// A new goal is the cheapest viewpoint within local_radius_m by path cost (ties by id); after
// local_misses_before_global steps without one, the cheapest anywhere. With FFF a candidate
// whose route needs a sharper turn than fff_turn_rate_rad_per_m allows is skipped
// (max_goal_candidates checked). A chooser set from outside (Python methods) replaces the rule.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/common/types.h"
#include "core/explorer/counters.h"
#include "core/explorer/explorer.h"
#include "core/methods/monospheres/map/reference_code.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "core/methods/monospheres/planner/sphere_graph_search.h"
#include "core/methods/monospheres/planner/viewpoint_set.h"

namespace msb {

/// The goal rule's parameters: part of MonoSpheresPlannerConfig (`planner.goals`), their keys flat
/// in `method.planner` (fff under `method.switches`).
struct GoalChoiceConfig {
  bool fff = true;                         ///< skip goals whose route needs too sharp a turn
  double fff_turn_rate_rad_per_m = 0.314;  ///< heading change allowed per metre before a viewpoint
  double local_radius_m = 15.0;            ///< local goals lie within this distance
  int local_misses_before_global = 3;      ///< steps without a local goal before searching all
  int max_goal_candidates = 10;            ///< FFF feasibility checks per list
  double reach_distance_m = 1.0;           ///< goal reached within ...
  double reach_angle_deg = 90.0;           ///< ... and this heading difference
  double no_progress_timeout_s = 10.0;     ///< goal failed without 0.5 m progress for this long
  int max_blocked_steps = 5;               ///< consecutive blocked steps fail the goal
};

/// A reachable viewpoint as a goal chooser sees it.
struct ViewpointCandidate {
  uint64_t id = 0;
  Vec3 position = Vec3::Zero();
  double yaw_rad = 0.0;
  double path_cost_m = 0.0;  ///< along the sphere graph from the vehicle
  int value = 0;             ///< frontiers it sees
};

/// What a viewpoint chooser is asked whenever MonoSpheres takes a new goal (estimate frame).
struct ViewpointRequest {
  double t_s = 0.0;
  Vec3 position = Vec3::Zero();                ///< the vehicle
  std::vector<ViewpointCandidate> candidates;  ///< reachable viewpoints by path cost (ties by id)
};

/// A goal chooser replacing MonoSpheres' goal rule (the goal-only helper for Python methods,
/// docs/python.md): nothing keeps MonoSpheres' own choice, 0 takes no goal this step, another
/// value is the id of one of the candidates (followed as MonoSpheres follows its goals; FFF's
/// feasibility check is the chooser's business).
using ViewpointChooser = std::function<std::optional<uint64_t>(const ViewpointRequest&)>;

/// How a goal ended (none: it goes on, or there was none).
enum class GoalEnd { kNone, kReached, kGone, kUnreachable, kNoProgress, kBlocked };

/// The route the vehicle would fly from `from` along a sphere path to `goal` (FFF's check).
using GoalRoute = std::function<std::vector<Vec3>(const Vec3& from, const SpherePath& path, const Vec3& goal)>;

/// The active goal and the rule that picks the next one, over a viewpoint set it marks
/// (reached, failed) and a map it reads.
class GoalChoice {
 public:
  /// `route` builds the route FFF checks. Of the published code's switches it reads
  /// heading_check_signed (the difference goal − current, wrapped to [−π, π), passes when below
  /// reach_angle_deg, without abs()) and turn_check_without_fff (goals skipped as with FFF).
  GoalChoice(const GoalChoiceConfig& config, const ReferenceCodeConfig& reference_code, ViewpointSet& viewpoints,
             const SphereMap& map, GoalRoute route);

  /// The active goal's viewpoint id (0 = none).
  uint64_t goal() const { return goal_; }
  /// Goals from `chooser` instead of the rule (asked whenever a new goal is taken).
  void setChooser(ViewpointChooser chooser) { chooser_ = std::move(chooser); }

  /// Ends the active goal if its viewpoint is gone, it is reached (vehicle pose), its sphere is
  /// not in `field` or it made no progress for too long. Returns how it ended.
  GoalEnd checkActive(const VehicleState& s, const SphereCostField& field);
  /// Without an active goal: asks the chooser, else the rule. True if a goal was taken;
  /// `*global` says whether the rule had to search beyond local_radius_m.
  bool takeNew(const VehicleState& s, const SphereCostField& field, bool* global);
  /// Fails the active goal now (blacklists its viewpoint).
  void fail(double t_s);
  /// Drops the active goal without failing it (its viewpoint stays a candidate).
  void drop() { goal_ = 0; }
  /// The route to the goal is `remaining_m` long at t_s: progress is 0.5 m shorter than the best.
  void noteRemaining(double remaining_m, double t_s);
  /// A blocked step (the route's start too close to an obstacle point); true if that failed the goal.
  bool noteBlocked(double t_s);
  /// A step that was not blocked.
  void noteUnblocked() { blocked_steps_ = 0; }
  /// When the goal last made progress (or was taken).
  double lastProgress() const { return last_progress_s_; }

 private:
  std::optional<uint64_t> rule(const VehicleState& s, const SphereCostField& field, bool* global);
  std::optional<uint64_t> pickFeasible(const VehicleState& s, const SphereCostField& field,
                                       const std::vector<std::pair<double, uint64_t>>& list) const;
  std::optional<uint64_t> askChooser(const VehicleState& s, const SphereCostField& field, bool* asked) const;

  GoalChoiceConfig config_;
  ReferenceCodeConfig reference_code_;
  ViewpointSet& viewpoints_;
  const SphereMap& map_;
  GoalRoute route_;
  ViewpointChooser chooser_;
  uint64_t goal_ = 0;
  double best_remaining_m_ = 1e18, last_progress_s_ = 0;
  int local_misses_ = 0, blocked_steps_ = 0;
};

}  // namespace msb
