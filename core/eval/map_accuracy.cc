#include "core/eval/map_accuracy.h"

#include <cmath>

namespace msb {

std::optional<double> MapAccuracy::nearSurfaceShare() const {
  if (obstacles == 0) return std::nullopt;
  return double(obstacles_near_surface) / double(obstacles);
}

std::optional<double> MapAccuracy::reallyFreeShare() const {
  if (free_elements == 0) return std::nullopt;
  return double(free_really_free) / double(free_elements);
}

std::optional<double> MapAccuracy::falselyFreeVolumeShare() const {
  if (!(free_volume_m3 > 0)) return std::nullopt;
  return falsely_free_volume_m3 / free_volume_m3;
}

std::optional<double> MapAccuracy::falselyFreeElementShare() const {
  if (free_elements == 0) return std::nullopt;
  return double(free_elements_falsely_free) / double(free_elements);
}

ElementFalseFree elementFalseFree(const FreeSpaceElement& e, const WorldTruth& truth, double tol) {
  const bool ball = e.footprint == FreeSpaceElement::Footprint::kDisk;
  const double r = e.radius;
  ElementFalseFree out;
  out.volume_m3 = ball ? 4.0 / 3.0 * M_PI * r * r * r : 8.0 * r * r * r;
  // Every point of the element lies within `reach` of its centre: free enough as a whole?
  const double reach = ball ? r : r * std::sqrt(3.0);
  if (truth.distance(e.centre, reach + 1.0) - reach >= -tol) return out;
  constexpr int n = 8;
  const double step = 2.0 * r / n;
  int inside = 0, bad = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        const Vec3 q = Vec3(a + 0.5, b + 0.5, c + 0.5) * step - Vec3::Constant(r);
        if (ball && q.squaredNorm() > r * r) continue;
        ++inside;
        bad += truth.distance(e.centre + q, tol + 1.0) < -tol;
      }
  if (inside > 0) out.falsely_free_m3 = out.volume_m3 * double(bad) / double(inside);
  return out;
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
  for (const auto& d : map.free_space) {
    a.free_really_free += truth.distance(d.centre, 5.0) > 0.0;
    const ElementFalseFree f = elementFalseFree(d, truth);
    a.free_volume_m3 += f.volume_m3;
    a.falsely_free_volume_m3 += f.falsely_free_m3;
    a.free_elements_falsely_free += f.falsely_free_m3 > 0;
  }
  return a;
}

}  // namespace msb
