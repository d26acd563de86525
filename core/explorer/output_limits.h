// The contract on a method's output (docs/metrics.md, "Limits"): what free space and waypoints a
// method may hand out. Part of the method interface, so that the loop, the metric and the
// Python layer check the same limits; output beyond them ends the run as an error
// (MethodOutputError) naming the element or waypoint and the tick. The limits bound the metric's
// work per sample and keep every figure finite.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/common/aabb.h"
#include "core/common/messages.h"
#include "core/explorer/snapshot.h"

namespace msb {

/// The most free-space elements one sample may hold.
inline constexpr size_t kMaxFreeSpaceElements = 5'000'000;
/// The largest radius (or half side) of a free-space element, m.
inline constexpr double kMaxElementRadiusM = 250.0;
/// The largest total footprint of one sample's free space, m²: the sum over its elements of a
/// disk's πr² or a square's (2r)². The metric's work grows with it (each element is tested in
/// every column it covers); honest maps measured at 1 200–36 000 m² (docs/metrics.md, "Limits").
inline constexpr double kMaxFreeSpaceFootprintM2 = 1e6;
/// The farthest an element's centre may lie outside the exploration box, m.
inline constexpr double kMaxElementOffsetM = 1000.0;
/// The farthest a waypoint may lie from the start, m.
inline constexpr double kMaxWaypointDistanceM = 1000.0;

/// What is wrong with the free space (NaN, negative or too large radius, centre not finite or
/// too far from `box`, too many elements, too large a total footprint), naming the element;
/// nullopt when it is within limits.
std::optional<std::string> freeSpaceProblem(const std::vector<FreeSpaceElement>& free_space, const Aabb& box);

/// What is wrong with a waypoint (not finite, or farther than kMaxWaypointDistanceM from
/// `start`): "is not finite" or "lies … m from the start (…)"; nullopt when it is within limits.
std::optional<std::string> waypointProblem(const Waypoint& w, const Vec3& start);

}  // namespace msb
