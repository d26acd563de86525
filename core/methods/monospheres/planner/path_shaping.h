// Turning a sphere path into waypoints for the trajectory tracker (docs/architecture.md §8): shortcutting
// inside the free space, and the heading of each waypoint with and without forced forward
// flight (FFF).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/common/messages.h"

namespace msb {

/// True if the straight segment a→b is safe to fly.
using SegmentCheck = std::function<bool(const Vec3& a, const Vec3& b)>;

/// Greedy shortcutting: from each kept point, jump to the farthest later point (at most
/// `max_skip` ahead) that the check accepts; consecutive points are always kept connected.
/// The first and last points are always kept.
std::vector<Vec3> shortcutPath(const std::vector<Vec3>& points, const SegmentCheck& free, int max_skip = 12);

/// Polyline length.
double pathLength(const std::vector<Vec3>& points);

/// Heading rules for a path ending at a viewpoint.
struct HeadingPlan {
  std::vector<Waypoint> waypoints;  ///< the path without its first point (the vehicle)
  double turn_needed_rad = 0.0;     ///< |goal heading − final travel direction| (FFF)
  double turn_stretch_m = 0.0;      ///< length of the final stretch in which the turn happens
  bool feasible = true;             ///< false if FFF's turn does not fit into the path
};

/// Assigns headings. With FFF, waypoints face the direction of travel except in the final
/// stretch of length |Δψ| / turn_rate_per_m, where the heading turns linearly with distance
/// from the travel direction to the goal heading (waypoints every `spacing_m` there); if the
/// path is shorter than that stretch the plan is infeasible. Without FFF every waypoint carries
/// the goal heading (the reference's behaviour). When the vehicle is already inside the final
/// stretch (re-planning during the approach) and `current_heading_rad` is given, the heading
/// turns from the current heading to the goal heading over the whole remaining path.
HeadingPlan assignHeadings(const std::vector<Vec3>& points, double goal_heading_rad, bool fff, double turn_rate_per_m,
                           double spacing_m = 1.0, std::optional<double> current_heading_rad = std::nullopt);

}  // namespace msb
