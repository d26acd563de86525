#include "core/methods/monospheres/planner/goal_choice.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/methods/monospheres/planner/path_shaping.h"

namespace msb {

GoalChoice::GoalChoice(const GoalChoiceConfig& config, const ReferenceCodeConfig& reference_code,
                       ViewpointSet& viewpoints, const SphereMap& map, GoalRoute route)
    : config_(config), reference_code_(reference_code), viewpoints_(viewpoints), map_(map), route_(std::move(route)) {}

GoalEnd GoalChoice::checkActive(const VehicleState& s, const SphereCostField& field) {
  // The active goal: gone (VPB), reached, unreachable or without progress.
  if (goal_ && !viewpoints_.viewpoints().count(goal_)) {
    goal_ = 0;
    return GoalEnd::kGone;
  }
  if (!goal_) return GoalEnd::kNone;
  const Vec3 p = s.T_W_B.translation();
  const double yaw = yawOf(s.T_W_B.linear());
  const Viewpoint& v = viewpoints_.viewpoints().at(goal_);
  const double heading_diff = wrapAngle(v.yaw_rad - yaw);
  if ((v.position - p).norm() <= config_.reach_distance_m &&
      (reference_code_.heading_check_signed ? heading_diff : std::abs(heading_diff)) <=
          config_.reach_angle_deg * kDeg) {
    viewpoints_.markReached(goal_, map_, p, yaw);
    goal_ = 0;
    return GoalEnd::kReached;
  }
  if (!field.cost.count(v.sphere)) {
    fail(s.t_s);
    return GoalEnd::kUnreachable;
  }
  if (s.t_s - last_progress_s_ > config_.no_progress_timeout_s) {
    fail(s.t_s);
    return GoalEnd::kNoProgress;
  }
  return GoalEnd::kNone;
}

bool GoalChoice::takeNew(const VehicleState& s, const SphereCostField& field, bool* global) {
  *global = false;
  bool asked = false;
  std::optional<uint64_t> g = askChooser(s, field, &asked);
  if (!asked) g = rule(s, field, global);
  if (!g || *g == 0) return false;
  goal_ = *g;
  last_progress_s_ = s.t_s;
  best_remaining_m_ = 1e18;
  blocked_steps_ = 0;
  return true;
}

void GoalChoice::fail(double t_s) {
  viewpoints_.markFailed(goal_, t_s);
  goal_ = 0;
}

void GoalChoice::noteRemaining(double remaining_m, double t_s) {
  if (remaining_m < best_remaining_m_ - 0.5) best_remaining_m_ = remaining_m, last_progress_s_ = t_s;
}

bool GoalChoice::noteBlocked(double t_s) {
  if (++blocked_steps_ < config_.max_blocked_steps) return false;
  fail(t_s);
  blocked_steps_ = 0;
  return true;
}

std::optional<uint64_t> GoalChoice::pickFeasible(const VehicleState& s, const SphereCostField& field,
                                                 const std::vector<std::pair<double, uint64_t>>& list) const {
  // The first of the cheapest max_goal_candidates whose route FFF can fly (any, without FFF,
  // unless the published turn check stays).
  int tries = 0;
  for (const auto& [cost, id] : list) {
    if (tries++ >= config_.max_goal_candidates) break;
    if (!config_.fff && !reference_code_.turn_check_without_fff) return id;
    const Viewpoint& v = viewpoints_.viewpoints().at(id);
    const auto pts = route_(s.reference.position_m, field.pathTo(v.sphere), v.position);
    if (assignHeadings(pts, v.yaw_rad, true, config_.fff_turn_rate_rad_per_m).feasible) return id;
  }
  return std::nullopt;
}

std::optional<uint64_t> GoalChoice::rule(const VehicleState& s, const SphereCostField& field, bool* global) {
  // Reachable viewpoints by path cost (ties by id), local ones apart.
  const Vec3 p = s.T_W_B.translation();
  std::vector<std::pair<double, uint64_t>> local, all;
  for (const auto& [id, v] : viewpoints_.viewpoints()) {
    const auto it = field.cost.find(v.sphere);
    if (it == field.cost.end()) continue;
    all.emplace_back(it->second, id);
    if ((v.position - p).norm() <= config_.local_radius_m) local.emplace_back(it->second, id);
  }
  std::sort(local.begin(), local.end());
  std::sort(all.begin(), all.end());
  // Local first; after enough misses, anywhere.
  if (auto id = pickFeasible(s, field, local)) {
    local_misses_ = 0;
    return id;
  }
  if (++local_misses_ <= config_.local_misses_before_global) return std::nullopt;
  if (auto id = pickFeasible(s, field, all)) {
    local_misses_ = 0;
    *global = true;
    return id;
  }
  return std::nullopt;
}

std::optional<uint64_t> GoalChoice::askChooser(const VehicleState& s, const SphereCostField& field, bool* asked) const {
  // The reachable viewpoints by path cost for the chooser; its answer, checked.
  *asked = false;
  if (!chooser_) return std::nullopt;
  ViewpointRequest q{s.t_s, s.T_W_B.translation(), {}};
  for (const auto& [id, v] : viewpoints_.viewpoints()) {
    const auto it = field.cost.find(v.sphere);
    if (it != field.cost.end()) q.candidates.push_back({id, v.position, v.yaw_rad, it->second, v.value});
  }
  std::stable_sort(
      q.candidates.begin(), q.candidates.end(),
      [](const ViewpointCandidate& a, const ViewpointCandidate& b) { return a.path_cost_m < b.path_cost_m; });
  const std::optional<uint64_t> id = chooser_(q);
  if (!id) return std::nullopt;
  *asked = true;
  if (*id != 0 &&
      std::none_of(q.candidates.begin(), q.candidates.end(), [&](const ViewpointCandidate& c) { return c.id == *id; }))
    throw std::runtime_error("the viewpoint chooser chose " + std::to_string(*id) + ", not a candidate");
  return id;
}

}  // namespace msb
