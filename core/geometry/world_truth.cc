#include "core/geometry/world_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace msb {

WorldTruth::WorldTruth(std::vector<Shape> shapes, double index_cell_m)
    : shapes_(std::move(shapes)), cell_(index_cell_m) {
  bounds_.reserve(shapes_.size());
  for (const Shape& s : shapes_)
    bounds_.push_back(s.type == ShapeType::kHalfSpace ? std::pair<Vec3, Vec3>() : s.bounds());
  // Grid over the union of the bounded shapes' footprints.
  Vec2 lo = Vec2::Constant(1e18), hi = Vec2::Constant(-1e18);
  for (size_t i = 0; i < shapes_.size(); ++i) {
    if (shapes_[i].type == ShapeType::kHalfSpace) {
      unbounded_.push_back(static_cast<int>(i));
      continue;
    }
    const auto [mn, mx] = shapes_[i].bounds();
    lo = lo.cwiseMin(mn.head<2>());
    hi = hi.cwiseMax(mx.head<2>());
  }
  if (lo.x() > hi.x()) lo = hi = Vec2::Zero();
  origin_ = lo;
  nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell_)) + 1);
  cells_.assign(static_cast<size_t>(nx_) * ny_, {});
  for (size_t i = 0; i < shapes_.size(); ++i) {
    if (shapes_[i].type == ShapeType::kHalfSpace) continue;
    const auto [mn, mx] = shapes_[i].bounds();
    const int x0 = std::clamp(int((mn.x() - origin_.x()) / cell_), 0, nx_ - 1);
    const int x1 = std::clamp(int((mx.x() - origin_.x()) / cell_), 0, nx_ - 1);
    const int y0 = std::clamp(int((mn.y() - origin_.y()) / cell_), 0, ny_ - 1);
    const int y1 = std::clamp(int((mx.y() - origin_.y()) / cell_), 0, ny_ - 1);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) cells_[size_t(y) * nx_ + x].push_back(static_cast<int>(i));
  }
}

template <class F>
void WorldTruth::forCell(int cx, int cy, F&& f) const {
  if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return;
  for (int i : cells_[size_t(cy) * nx_ + cx]) f(i);
}

NearestObstacle WorldTruth::nearest(const Vec3& p, double max_range_m) const {
  NearestObstacle best{max_range_m, -1};
  auto consider = [&](int i) {
    const double d = shapes_[i].signedDistance(p);
    if (d < best.distance_m || (d == best.distance_m && i < best.shape)) best = {d, i};
  };
  for (int i : unbounded_) consider(i);
  // Rings of cells around p; ring k lies at least (k − 1) cells away.
  const int cx = int(std::floor((p.x() - origin_.x()) / cell_));
  const int cy = int(std::floor((p.y() - origin_.y()) / cell_));
  const int max_ring = std::max(nx_, ny_) + std::abs(cx) + std::abs(cy) + 1;
  for (int k = 0; k <= max_ring; ++k) {
    if ((k - 1) * cell_ > best.distance_m) break;
    for (int x = cx - k; x <= cx + k; ++x) {
      for (int y = cy - k; y <= cy + k; ++y) {
        if (std::max(std::abs(x - cx), std::abs(y - cy)) != k) continue;
        forCell(x, y, consider);
      }
    }
  }
  return best;
}

const Shape* WorldTruth::shapeNamed(const std::string& name) const {
  for (const Shape& s : shapes_)
    if (s.name == name) return &s;
  return nullptr;
}

bool WorldTruth::inside(const Vec3& p) const {
  for (int i : unbounded_)
    if (shapes_[i].signedDistance(p) <= 0.0) return true;
  const int cx = int(std::floor((p.x() - origin_.x()) / cell_));
  const int cy = int(std::floor((p.y() - origin_.y()) / cell_));
  bool hit = false;
  forCell(cx, cy, [&](int i) { hit = hit || shapes_[i].signedDistance(p) <= 0.0; });
  return hit;
}

void WorldTruth::rayTestShape(int i, const Vec3& o, const Vec3& d, double max_range_m,
                              std::optional<RayHit>& best) const {
  // Cheap rejection by the bounding box (slab test).
  if (shapes_[i].type != ShapeType::kHalfSpace) {
    const auto& [mn, mx] = bounds_[i];
    double t0 = 0.0, t1 = max_range_m;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-15) {
        if (o[k] < mn[k] || o[k] > mx[k]) return;
        continue;
      }
      double a = (mn[k] - o[k]) / d[k], b = (mx[k] - o[k]) / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a), t1 = std::min(t1, b);
      if (t0 > t1) return;
    }
  }
  const auto t = shapes_[i].raycast(o, d);
  if (!t || *t > max_range_m) return;
  if (!best || *t < best->distance_m || (*t == best->distance_m && i < best->shape)) best = RayHit{*t, i};
}

std::optional<RayHit> WorldTruth::raycast(const Vec3& o, const Vec3& dir, double max_range_m) const {
  const Vec3 d = dir.normalized();
  std::optional<RayHit> best;
  for (size_t i = 0; i < shapes_.size(); ++i) rayTestShape(int(i), o, d, max_range_m, best);
  return best;
}

std::optional<RayHit> WorldTruth::raycastIndexed(const Vec3& o, const Vec3& dir, double max_range_m) const {
  const Vec3 d = dir.normalized();
  std::optional<RayHit> best;
  for (int i : unbounded_) rayTestShape(i, o, d, max_range_m, best);
  // The part of the ray over the grid: [t, t_end] (slab test against the grid's rectangle).
  double t = 0.0, t_end = max_range_m;
  const Vec2 lo = origin_, hi = origin_ + Vec2(nx_ * cell_, ny_ * cell_);
  for (int k = 0; k < 2; ++k) {
    if (std::abs(d[k]) < 1e-15) {
      if (o[k] < lo[k] || o[k] > hi[k]) return best;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t = std::max(t, a), t_end = std::min(t_end, b);
  }
  if (t > t_end) return best;
  // Walk the cells the ray's footprint crosses (Amanatides–Woo), nearest first; a shape spans
  // several cells, so each is tested once. Stop once the best hit lies before the next cell.
  std::vector<char> tested(shapes_.size(), 0);
  const Vec3 p = o + t * d;
  int c[2], step[2];
  double t_next[2], t_delta[2];
  for (int k = 0; k < 2; ++k) {
    c[k] = std::clamp(int(std::floor((p[k] - origin_[k]) / cell_)), 0, (k ? ny_ : nx_) - 1);
    step[k] = d[k] > 0 ? 1 : -1;
    const double edge = origin_[k] + (c[k] + (d[k] > 0 ? 1 : 0)) * cell_;
    t_delta[k] = std::abs(d[k]) < 1e-15 ? 1e300 : cell_ / std::abs(d[k]);
    t_next[k] = std::abs(d[k]) < 1e-15 ? 1e300 : (edge - o[k]) / d[k];
  }
  while (true) {
    forCell(c[0], c[1], [&](int i) {
      if (tested[size_t(i)]) return;
      tested[size_t(i)] = 1;
      rayTestShape(i, o, d, max_range_m, best);
    });
    const int k = t_next[0] < t_next[1] ? 0 : 1;
    const double leave = t_next[k];
    if ((best && best->distance_m <= leave) || leave > t_end) break;
    c[k] += step[k];
    t_next[k] += t_delta[k];
    if (c[k] < 0 || c[k] >= (k ? ny_ : nx_)) break;
  }
  return best;
}

std::vector<Column> WorldTruth::explorableColumns(const Aabb& box, double cell_m, double sample_m) const {
  std::vector<Column> out;
  const int nx = static_cast<int>(std::floor((box.max.x() - box.min.x()) / cell_m + 1e-9));
  const int ny = static_cast<int>(std::floor((box.max.y() - box.min.y()) / cell_m + 1e-9));
  const int ns = std::max(1, static_cast<int>(std::round(cell_m / sample_m)));
  const int nz = std::max(1, static_cast<int>(std::round((box.max.z() - box.min.z()) / sample_m)));
  const double step_xy = cell_m / ns, step_z = (box.max.z() - box.min.z()) / nz;
  for (int ix = 0; ix < nx; ++ix) {
    for (int iy = 0; iy < ny; ++iy) {
      bool free = false;
      // Sample at lattice-cell centres, top layers first (columns are mostly blocked low).
      for (int kz = nz - 1; kz >= 0 && !free; --kz)
        for (int a = 0; a < ns && !free; ++a)
          for (int b = 0; b < ns && !free; ++b) {
            const Vec3 p(box.min.x() + ix * cell_m + (a + 0.5) * step_xy,
                         box.min.y() + iy * cell_m + (b + 0.5) * step_xy, box.min.z() + (kz + 0.5) * step_z);
            free = !inside(p);
          }
      if (free) out.push_back({ix, iy});
    }
  }
  return out;
}

}  // namespace msb
