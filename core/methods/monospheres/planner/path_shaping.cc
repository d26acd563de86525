#include "core/methods/monospheres/planner/path_shaping.h"

#include <algorithm>
#include <cmath>

namespace msb {

std::vector<Vec3> shortcutPath(const std::vector<Vec3>& pts, const SegmentCheck& free, int max_skip) {
  if (pts.size() <= 2) return pts;
  std::vector<Vec3> out = {pts.front()};
  size_t i = 0;
  while (i + 1 < pts.size()) {
    size_t next = i + 1;
    const size_t last = std::min(pts.size() - 1, i + size_t(std::max(1, max_skip)));
    for (size_t j = last; j > i + 1; --j)
      if (free(pts[i], pts[j])) {
        next = j;
        break;
      }
    out.push_back(pts[next]);
    i = next;
  }
  return out;
}

double pathLength(const std::vector<Vec3>& pts) {
  double l = 0;
  for (size_t i = 1; i < pts.size(); ++i) l += (pts[i] - pts[i - 1]).norm();
  return l;
}

HeadingPlan assignHeadings(const std::vector<Vec3>& pts, double goal_heading, bool fff, double turn_rate_per_m,
                           double spacing_m, std::optional<double> current_heading) {
  HeadingPlan plan;
  if (pts.size() < 2) {
    if (!pts.empty()) plan.waypoints.push_back({pts.back(), goal_heading});
    return plan;
  }
  if (!fff) {
    for (size_t i = 1; i < pts.size(); ++i) plan.waypoints.push_back({pts[i], goal_heading});
    return plan;
  }
  // Travel direction of the final approach (last segment with horizontal extent).
  double travel = goal_heading;
  for (size_t i = pts.size() - 1; i >= 1; --i) {
    const Vec3 d = pts[i] - pts[i - 1];
    if (std::hypot(d.x(), d.y()) > 0.2) {
      travel = std::atan2(d.y(), d.x());
      break;
    }
  }
  double delta = wrapAngle(goal_heading - travel);
  plan.turn_needed_rad = std::abs(delta);
  plan.turn_stretch_m = plan.turn_needed_rad / turn_rate_per_m;
  const double total = pathLength(pts);
  plan.feasible = plan.turn_stretch_m <= total + 1e-9;
  if (!plan.feasible && current_heading) {  // already turning: finish the turn over what is left
    travel = *current_heading;
    delta = wrapAngle(goal_heading - travel);
    plan.turn_stretch_m = total;
  }
  const double turn_start = std::max(0.0, total - plan.turn_stretch_m);

  // Walk the polyline; before turn_start waypoints face travel, after it they turn linearly.
  auto heading_at = [&](double s) {
    const double f = plan.turn_stretch_m > 0 ? std::clamp((s - turn_start) / plan.turn_stretch_m, 0.0, 1.0) : 1.0;
    return wrapAngle(travel + f * delta);
  };
  double s = 0;
  for (size_t i = 1; i < pts.size(); ++i) {
    const double len = (pts[i] - pts[i - 1]).norm();
    // Dense waypoints inside the turning stretch.
    double t = std::max(s, turn_start);
    if (plan.turn_stretch_m > 0 && t < s + len) {
      if (t > s + 1e-6) plan.waypoints.push_back({pts[i - 1] + (t - s) / len * (pts[i] - pts[i - 1]), std::nullopt});
      for (t += spacing_m; t < s + len - 1e-6; t += spacing_m)
        plan.waypoints.push_back({pts[i - 1] + (t - s) / len * (pts[i] - pts[i - 1]), heading_at(t)});
    }
    s += len;
    const bool turning = plan.turn_stretch_m > 0 && s > turn_start + 1e-6;
    plan.waypoints.push_back(
        {pts[i], turning || i + 1 == pts.size() ? std::optional<double>(heading_at(s)) : std::nullopt});
  }
  plan.waypoints.back().heading_rad = goal_heading;
  return plan;
}

}  // namespace msb
