#include "core/eval/map_accuracy.h"

namespace msb {

std::optional<double> MapAccuracy::nearSurfaceShare() const {
  if (obstacles == 0) return std::nullopt;
  return double(obstacles_near_surface) / double(obstacles);
}

std::optional<double> MapAccuracy::reallyFreeShare() const {
  if (free_elements == 0) return std::nullopt;
  return double(free_really_free) / double(free_elements);
}

int placementOf(const WorldTruth& truth, const Vec3& p) {
  const double d = truth.distance(p, 5.0);
  return d < -0.5 ? 0 : d <= 0.5 ? 1 : d <= 2.0 ? 2 : 3;
}

void countPlacement(PointPlacement& counts, int placement) {
  (placement == 0 ? counts.inside : placement == 1 ? counts.near_surface : counts.floating) += 1;
  counts.floating_far += placement == 3;
}

std::optional<MapAccuracy> mapAccuracy(const ExplorerSnapshot& map, const WorldTruth& truth) {
  if (map.obstacles.empty() && map.free_space.empty()) return std::nullopt;
  MapAccuracy a;
  a.obstacles = map.obstacles.size();
  a.free_elements = map.free_space.size();
  for (const auto& p : map.obstacles) a.obstacles_near_surface += placementOf(truth, p) == 1;
  for (const auto& d : map.free_space) a.free_really_free += truth.distance(d.centre, 5.0) > 0.0;
  return a;
}

}  // namespace msb
