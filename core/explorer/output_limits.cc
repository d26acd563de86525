#include "core/explorer/output_limits.h"

#include <cmath>

namespace msb {

std::optional<std::string> freeSpaceProblem(const std::vector<FreeSpaceElement>& free_space, const Aabb& box) {
  if (free_space.size() > kMaxFreeSpaceElements)
    return std::to_string(free_space.size()) + " free-space elements (the limit is " +
           std::to_string(kMaxFreeSpaceElements) + ")";
  double footprint_m2 = 0.0;
  for (size_t i = 0; i < free_space.size(); ++i) {
    const FreeSpaceElement& e = free_space[i];
    const std::string which = "free-space element " + std::to_string(i) + " (id " + std::to_string(e.id) + ")";
    if (!std::isfinite(e.radius) || e.radius < 0 || e.radius > kMaxElementRadiusM)
      return which + ": radius " + std::to_string(e.radius) + " m is not in [0, " +
             std::to_string(int(kMaxElementRadiusM)) + "] m";
    if (!e.centre.allFinite()) return which + ": its centre is not a finite point";
    const Vec3 outside = (box.min - e.centre).cwiseMax(e.centre - box.max).cwiseMax(0.0);
    if (outside.maxCoeff() > kMaxElementOffsetM)
      return which + ": its centre lies " + std::to_string(outside.maxCoeff()) +
             " m outside the exploration box (the limit is " + std::to_string(int(kMaxElementOffsetM)) + " m)";
    // The total footprint, the metric's work per sample.
    footprint_m2 +=
        e.footprint == FreeSpaceElement::Footprint::kSquare ? 4.0 * e.radius * e.radius : M_PI * e.radius * e.radius;
    if (footprint_m2 > kMaxFreeSpaceFootprintM2)
      return "the free space's total footprint passes " + std::to_string(int(kMaxFreeSpaceFootprintM2)) + " m² at " +
             which + " (the limit bounds the metric's work per sample)";
  }
  return std::nullopt;
}

std::optional<std::string> waypointProblem(const Waypoint& w, const Vec3& start) {
  if (!w.position_m.allFinite() || (w.heading_rad && !std::isfinite(*w.heading_rad))) return "is not finite";
  const double d = (w.position_m - start).norm();
  if (d > kMaxWaypointDistanceM)
    return "lies " + std::to_string(d) + " m from the start (the limit is " +
           std::to_string(int(kMaxWaypointDistanceM)) + " m)";
  return std::nullopt;
}

}  // namespace msb
