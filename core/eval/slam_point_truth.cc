#include "core/eval/slam_point_truth.h"

namespace msb {

PointTruth evaluatePoint(const SlamPoint& p, const Pose& T, const WorldTruth& truth, const FisheyeCamera& camera) {
  PointTruth out;
  const Vec3 ray = T.linear() * camera.unproject(p.anchor_pixel);
  const auto hit = truth.raycast(T.translation(), ray, 400.0);
  if (!hit) return out;
  out.has_surface = true;
  out.shape = hit->shape;
  out.true_depth_m = hit->distance_m;
  const Shape& shape = truth.shapes()[hit->shape];
  out.kind = shape.kind;
  const Vec3 p_true = T.translation() + hit->distance_m * ray;
  out.error_m = (p.p_W - p.T_W_anchor * (T.inverse() * p_true)).norm();
  // Silhouette points (a neighbour sees another shape: another object, or another part of one,
  // e.g. a vehicle's window on its body) have no single true surface: the corner is formed by
  // two. Such corners on textureless parts are real features; only interior points count as
  // "on" a textureless surface.
  out.interior = true;
  for (const Vec2& d : {Vec2(3, 0), Vec2(-3, 0), Vec2(0, 3), Vec2(0, -3)}) {
    const auto h = truth.raycast(T.translation(), T.linear() * camera.unproject(p.anchor_pixel + d), 400.0);
    if (!h || h->shape != hit->shape) {
      out.interior = false;
      break;
    }
  }
  out.textureless_interior = out.interior && shape.kind == ObstacleKind::kTextureless;
  return out;
}

const char* surfaceClass(const Shape& shape) {
  const std::string& n = shape.object.empty() ? shape.name : shape.object;
  auto starts = [&](const char* prefix) { return n.rfind(prefix, 0) == 0; };
  if (starts("ground") || starts("floor")) return "ground";
  if (starts("car") || starts("bus") || starts("fire_truck") || starts("truck") || starts("van")) return "vehicles";
  if (starts("tree")) return "trees";
  if (starts("rod") || starts("pole")) return "thin";
  if (starts("building") || starts("house") || starts("tower") || starts("wall") || starts("burned") ||
      starts("ruin") || starts("cave") || starts("rock") || starts("pillar"))
    return "walls";
  return "other";
}

}  // namespace msb
