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

Placement placementOf(const WorldTruth& truth, const Vec3& p) {
  const double d = truth.distance(p, 5.0);
  if (d < -0.5) return Placement::inside;
  if (d <= 0.5) return Placement::near_surface;
  return d <= 2.0 ? Placement::floating_near : Placement::floating_far;
}

void countPlacement(PointPlacement& counts, Placement placement) {
  switch (placement) {
    case Placement::inside:
      ++counts.inside;
      break;
    case Placement::near_surface:
      ++counts.near_surface;
      break;
    case Placement::floating_far:
      ++counts.floating_far;
      [[fallthrough]];
    case Placement::floating_near:
      ++counts.floating;
      break;
  }
}

std::optional<MapAccuracy> mapAccuracy(const ExplorerSnapshot& map, const WorldTruth& truth) {
  if (map.obstacles.empty() && map.free_space.empty()) return std::nullopt;
  MapAccuracy a;
  a.obstacles = map.obstacles.size();
  a.free_elements = map.free_space.size();
  for (const auto& p : map.obstacles) a.obstacles_near_surface += placementOf(truth, p) == Placement::near_surface;
  for (const auto& d : map.free_space) a.free_really_free += truth.distance(d.centre, 5.0) > 0.0;
  return a;
}

}  // namespace msb
