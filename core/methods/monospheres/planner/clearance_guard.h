// Clearance safety of the MonoSpheres planner (docs/planner.md): the rules that keep the vehicle
// and its path away from the map's obstacle points, apart from goal choice and the sphere graph.
// A sample is too close when it lies within `check_clearance_m` of an obstacle point (with
// `allow_moving_away`: only if it is also closer to that point than the vehicle, so a vehicle
// already inside a clearance may move away); a path is blocked when a sample of its first
// `check_ahead_m` is too close; a vehicle inside a clearance backs out along the weighted
// direction away from the points, `escape_margin_m` beyond it.
#pragma once

#include <optional>
#include <vector>

#include "core/common/types.h"
#include "core/explorer/takeoff.h"
#include "core/methods/monospheres/map/sphere_map.h"

namespace msb {

/// The clearance rules' parameters: part of MonoSpheresPlannerConfig (`planner.clearance`), their
/// keys flat in `method.planner`.
struct ClearanceConfig {
  bool allow_moving_away = true;  ///< a sample inside a clearance passes if it is farther than the vehicle
  double escape_margin_m = 0.3;   ///< a vehicle inside a clearance backs out this far beyond it
};

/// The clearance rules over a sphere map's obstacle points (the map is read, never changed).
class ClearanceGuard {
 public:
  /// `check`: how much of a path the blocked check samples (check_ahead_m) and the clearance from
  /// obstacle points (check_clearance_m).
  ClearanceGuard(const SphereMap& map, const PathCheckConfig& check, const ClearanceConfig& config)
      : map_(map), check_(check), config_(config) {}

  /// True if x lies within the clearance of an obstacle point and closer to it than `here`.
  bool approachesPoint(const Vec3& x, const Vec3& here) const;
  /// True if x lies within the clearance of an obstacle point; with allow_moving_away only if x
  /// is also closer to it than `here` (the vehicle).
  bool tooClose(const Vec3& x, const Vec3& here) const;
  /// True if no sample (0.3 m apart, ends included) of a→b is too close.
  bool segmentClear(const Vec3& a, const Vec3& b, const Vec3& here) const;
  /// True if a sample of the first check_ahead_m of the path (0.25 m apart) is too close, seen
  /// from its first point (the vehicle).
  bool pathBlocked(const std::vector<Vec3>& pts) const;
  /// Where to back away to when `here` lies inside an obstacle point's clearance; none when it is
  /// not inside one, or when the way out approaches another point.
  std::optional<Vec3> escape(const Vec3& here) const;

 private:
  const SphereMap& map_;
  PathCheckConfig check_;
  ClearanceConfig config_;
};

/// True if `ok` holds at every sample of the segment a→b: n + 1 evenly spaced points (ends
/// included), n = ceil(|b − a| / step) ≥ 1.
template <class Pred>
bool everySample(const Vec3& a, const Vec3& b, double step, Pred ok) {
  const int n = std::max(1, int(std::ceil((b - a).norm() / step)));
  for (int i = 0; i <= n; ++i)
    if (!ok(Vec3(a + (double(i) / n) * (b - a)))) return false;
  return true;
}

}  // namespace msb
