#include "core/methods/grid_random/grid_explorer.h"

#include <algorithm>
#include <cmath>

namespace msb {

void GridExplorerConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  // Leaves keyed into cells under half their size leave every other key plane empty: no two
  // slabs of the planning tree would ever connect.
  const double tree = planner.planning_tree_resolution_m;
  c.require(tree == 0.0 || tree >= 0.5 * map.resolution_m, "planner.planning_tree_resolution_m",
            "must be 0 (plan on the map's cells) or at least half the map's resolution (" +
                std::to_string(map.resolution_m) + " m): finer, no key plane of the tree connects to the next");
}

namespace {
// `replanning_counter_ >= 2` (octomap_planner.cpp timerMain, 935): the planner gives up.
constexpr int kReferenceFailuresBeforeIdle = 2;

// The planner's cell size: the planning tree's, or the map's.
double plannerResolution(const GridExplorerConfig& c) {
  return c.planner.planning_tree_resolution_m > 0 ? c.planner.planning_tree_resolution_m : c.map.resolution_m;
}
}  // namespace

GridExplorer::GridExplorer(const GridExplorerConfig& config, const ExplorerContext& context)
    : config_(checkValid(config)),
      context_(context),
      map_(config.map),
      planner_(config_.planner, context.exploration_box, plannerResolution(config_)),
      goal_rng_(context.seed, "baseline_goals"),
      takeoff_(context.start, config) {}

void GridExplorer::observe(const SlamPointsFrame& frame) {
  counters_[GridCounter::kMapPoints] += map_.insert(frame).points;
  map_changed_ = true;
}

Vec3 GridExplorer::drawGoal(const Vec3& p) {
  // Uniform in the square around the vehicle intersected with the box, height in the band.
  const Aabb& box = context_.exploration_box;
  const double h = 0.5 * config_.goal_square_m;
  Vec2 lo = (p.head<2>() - Vec2::Constant(h)).cwiseMax(box.min.head<2>());
  Vec2 hi = (p.head<2>() + Vec2::Constant(h)).cwiseMin(box.max.head<2>());
  if ((hi.array() < lo.array()).any()) lo = box.min.head<2>(), hi = box.max.head<2>();  // vehicle far outside
  double z_lo = std::max(box.min.z(), config_.goal_min_altitude_m);
  double z_hi = box.max.z() - config_.goal_ceiling_margin_m;
  if (z_hi < z_lo) z_lo = z_hi = 0.5 * (box.min.z() + box.max.z());
  const double x = goal_rng_.uniform(lo.x(), hi.x()), y = goal_rng_.uniform(lo.y(), hi.y());
  const double z = goal_rng_.uniform(z_lo, z_hi);
  return Vec3(x, y, z);
}

PathCommand GridExplorer::command(const VehicleState& s, std::vector<Waypoint> w) {
  return sendPath(s, std::move(w), last_path_, counters_[GridCounter::kPathsSent]);
}

std::optional<PathCommand> GridExplorer::plan(const VehicleState& s) {
  return takeOffThenExplore(
      takeoff_, s, [&](std::vector<Waypoint> w) { return command(s, std::move(w)); }, [&] { return explore(s); });
}

bool GridExplorer::pathBlocked(const Vec3& from) const {
  return pathNearOccupied(map_, last_path_, from, config_.check_ahead_m, config_.check_clearance_m);
}

std::optional<PathCommand> GridExplorer::explore(const VehicleState& s) {
  // Goal bookkeeping every goal period; nothing to do without a goal (after a chooser dropped
  // the goal in flight: stop once).
  if (s.t_s - last_goal_check_s_ >= config_.goal_period_s - 1e-9 && checkGoal(s))
    return command(s, {{s.reference.position_m, std::nullopt}});
  if (!goal_) return std::nullopt;

  // The predicted-path check: stop and re-plan when the path ahead nears an occupied cell.
  if (path_sent_ && !s.path_finished && pathBlocked(s.reference.position_m)) {
    ++counters_[GridCounter::kBlockedStops];
    replan_now_ = true;
    last_plan_s_ = s.t_s;
    given_path_.clear();  // a chooser's path too: A* from here on
    flying_given_ = false;
    return command(s, {{s.reference.position_m, std::nullopt}});
  }
  return replan(s);
}

bool GridExplorer::checkGoal(const VehicleState& s) {
  // Reached, idle or timed out → a new goal: drawn, or asked of the chooser (which is asked at
  // every check and may change the goal any time). Returns whether the vehicle must stop.
  const Vec3 p = s.T_W_B.translation();
  last_goal_check_s_ = s.t_s;
  bool need_goal = !goal_;
  if (goal_ && (*goal_ - p).norm() <= config_.reach_distance_m) {
    ++counters_[GridCounter::kGoalsReached];
    need_goal = true;
  } else if (goal_ && (idle_ || (path_sent_ && s.path_finished))) {
    ++counters_[GridCounter::kGoalsIdle];  // arrived at the closest reachable cell, or nowhere to go
    need_goal = true;
  } else if (goal_ && s.t_s - goal_since_s_ >= config_.goal_timeout_s) {
    ++counters_[GridCounter::kGoalsTimedOut];
    need_goal = true;
  }
  if (!chooser_) {
    if (need_goal) setGoal(s.t_s, drawGoal(p));
    return false;
  }
  const std::optional<std::vector<Vec3>> choice = chooser_(GoalRequest{s.t_s, p, need_goal, &map_});
  const bool moving = path_sent_ && !s.path_finished;
  if (!choice) {
    if (need_goal) setGoal(s.t_s, std::nullopt);
    return false;
  }
  if (choice->empty()) {
    setGoal(s.t_s, std::nullopt);
    return moving;  // no goal: hover where the reference is
  }
  setGoal(s.t_s, choice->back(), choice->size() > 1 ? *choice : std::vector<Vec3>{});
  return false;
}

void GridExplorer::setGoal(double t_s, std::optional<Vec3> goal, std::vector<Vec3> path) {
  goal_ = goal;
  given_path_ = std::move(path);
  flying_given_ = false;
  goal_since_s_ = t_s;
  path_sent_ = false;
  replan_now_ = true;
  failures_ = 0;
  idle_ = false;
  if (goal_) ++counters_[GridCounter::kGoalsChosen];
}

std::optional<PathCommand> GridExplorer::replan(const VehicleState& s) {
  // Re-plan every replan period (or at once after a new goal or a stop); a chooser's path is
  // sent once and flown as given.
  if (!replan_now_ && s.t_s - last_plan_s_ < config_.replan_period_s - 1e-9) return std::nullopt;
  if (flying_given_ || idle_) return std::nullopt;  // idle: nothing until a new goal
  replan_now_ = false;
  last_plan_s_ = s.t_s;
  if (!given_path_.empty()) {
    std::vector<Waypoint> w;
    for (const Vec3& q : given_path_) w.push_back({q, std::nullopt});
    path_sent_ = flying_given_ = true;
    return command(s, std::move(w));
  }
  // The planning tree is built around the start at every plan (createPlanningTree); the
  // map's cells only when the map changed.
  if (planner_.usesPlanningTree()) {
    planner_.rebuild(map_, s.reference.position_m);
  } else if (map_changed_) {
    planner_.rebuild(map_);
    map_changed_ = false;
  }
  const bool moving = path_sent_ && !s.path_finished;
  const int budget = expansionBudget(moving);
  const std::optional<GridPath> path = planner_.plan(s.reference.position_m, *goal_, budget);
  if (path && budget >= 0 && path->expansions >= budget && !path->reaches_goal)
    ++counters_[GridCounter::kPathsOverBudget];
  const bool too_short = config_.reference_failures && path && path->points.size() >= 2 &&
                         (path->points.back() - path->points.front()).norm() < config_.min_path_length_m;
  if (!path || path->points.size() < 2 || too_short) return planFailed(s);
  if (path->reaches_goal || !config_.reference_failures) failures_ = 0;  // the reference: a complete path only
  if (!path->reaches_goal) ++counters_[GridCounter::kPathsToClosestCell];
  path_sent_ = true;
  return command(s, pathWaypoints(path->points));
}

int GridExplorer::expansionBudget(bool moving) const {
  // The reference's clock (findPath) runs from before the planning tree is built; a hovering
  // vehicle's plan gets timeout + 1.5^failures (timerMain, 944-951). -1: no budget.
  const double timeout = config_.planner.time_budget_s;
  if (timeout <= 0) return -1;
  const double t = moving ? timeout : timeout + std::pow(1.5, double(failures_));
  const double left = t - planner_.treeWork().seconds();
  if (left <= 0) return 0;
  return int(std::min(1e9, std::floor(left / kGridBudgetCosts.per_expansion_s)));
}

std::optional<PathCommand> GridExplorer::planFailed(const VehicleState& s) {
  ++counters_[GridCounter::kPathsFailed];
  if (!config_.reference_failures) {
    path_sent_ = true;  // nothing to fly: idle, a new goal at the next goal check
    return command(s, {{s.reference.position_m, std::nullopt}});
  }
  // The reference sends nothing: the last trajectory goes on; it tries again at once, and
  // after two failures in a row it is idle until a new goal comes.
  if (++failures_ >= kReferenceFailuresBeforeIdle) {
    idle_ = true;
  } else {
    replan_now_ = true;
  }
  return std::nullopt;
}

std::vector<FreeSpaceElement> GridExplorer::freeSpace() const { return freeLeaves(map_); }

ExplorerSnapshot GridExplorer::snapshot() const { return gridSnapshot(map_, goal_, last_path_); }

std::map<std::string, double> GridExplorer::counters() const {
  Counters<GridCounter> c = counters_;
  const auto& tree = map_.tree();
  c[GridCounter::kLeaves] = double(tree.getNumLeafNodes());
  c[GridCounter::kMapMemoryMb] = double(tree.memoryUsage()) / (1024.0 * 1024.0);
  return c.toMap();
}

}  // namespace msb
