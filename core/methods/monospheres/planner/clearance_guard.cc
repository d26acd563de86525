#include "core/methods/monospheres/planner/clearance_guard.h"

#include <algorithm>
#include <cmath>

namespace msb {

bool ClearanceGuard::approachesPoint(const Vec3& x, const Vec3& here) const {
  for (uint64_t id : map_.obstaclesNear(x, check_.check_clearance_m)) {
    const Vec3& o = map_.obstacles().at(id).position;
    if ((x - o).norm() < (here - o).norm() - 1e-6) return true;
  }
  return false;
}

bool ClearanceGuard::tooClose(const Vec3& x, const Vec3& here) const {
  if (!config_.allow_moving_away) return map_.anyObstacleNear(x, check_.check_clearance_m);
  return approachesPoint(x, here);
}

bool ClearanceGuard::segmentClear(const Vec3& a, const Vec3& b, const Vec3& here) const {
  return everySample(a, b, 0.3, [&](const Vec3& x) { return !tooClose(x, here); });
}

bool ClearanceGuard::pathBlocked(const std::vector<Vec3>& pts) const {
  if (pts.empty()) return false;
  double s = 0;
  for (size_t i = 1; i < pts.size() && s < check_.check_ahead_m; ++i) {
    const Vec3 a = pts[i - 1], b = pts[i];
    const double len = (b - a).norm();
    for (double t = 0; t < len && s + t < check_.check_ahead_m; t += 0.25)
      if (tooClose(a + t / len * (b - a), pts.front())) return true;
    s += len;
  }
  return false;
}

std::optional<Vec3> ClearanceGuard::escape(const Vec3& here) const {
  // Away from the points within the clearance, each weighted by how deep inside it is, far
  // enough to leave the nearest one's clearance (plus a margin); the segment may not approach
  // any point it passes (the approach rule, whatever allow_moving_away says: escaping happens
  // inside a clearance by definition).
  const double clearance = check_.check_clearance_m;
  const std::vector<uint64_t> near = map_.obstaclesNear(here, clearance);
  if (near.empty()) return std::nullopt;
  Vec3 dir = Vec3::Zero();
  double d_min = clearance;
  for (uint64_t id : near) {
    const Vec3 away = here - map_.obstacles().at(id).position;
    const double d = away.norm();
    if (d < 1e-6) continue;
    dir += away / d * (clearance - d);
    d_min = std::min(d_min, d);
  }
  if (dir.norm() < 1e-6) return std::nullopt;
  const Vec3 target = here + dir.normalized() * (clearance - d_min + config_.escape_margin_m);
  if (!everySample(here, target, 0.1, [&](const Vec3& x) { return !approachesPoint(x, here); })) return std::nullopt;
  return target;
}

}  // namespace msb
