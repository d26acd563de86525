#include "core/eval/verified_coverage.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace msb {

bool elementContains(const PlacedElement& e, const Vec3& p) {
  const Vec3 q = p - e.centre;
  if (e.footprint == FreeSpaceElement::Footprint::kDisk) return q.squaredNorm() <= e.radius * e.radius;
  const double c = std::cos(e.yaw_rad), s = std::sin(e.yaw_rad);
  return std::abs(c * q.x() + s * q.y()) <= e.radius && std::abs(-s * q.x() + c * q.y()) <= e.radius &&
         std::abs(q.z()) <= e.radius;
}

VerifiedCoverage::VerifiedCoverage(const WorldTruth& truth, const FisheyeCamera& camera,
                                   const VerifiedCoverageConfig& config)
    : truth_(truth), config_(config), range_m_(camera.config().clip_far_m), verified_(config.cell_m) {
  if (!(config.z_hi_m > config.z_lo_m)) throw std::invalid_argument("VerifiedCoverage: empty flight heights");
  if (!(config.lattice_m > 0) || !(config.ray_spacing_px > 0) || !(config.free_tolerance_m >= 0))
    throw std::invalid_argument("VerifiedCoverage: lattice, ray spacing and tolerance must be positive");
  // The sampled pixels: a grid of ray_spacing_px full-resolution pixels, centred on the image.
  const double step = config.ray_spacing_px * camera.config().scale;
  for (double v = 0.5 * std::fmod(camera.height() - 1.0, step); v < camera.height(); v += step)
    for (double u = 0.5 * std::fmod(camera.width() - 1.0, step); u < camera.width(); u += step)
      if (camera.pixelInFov(Vec2(u, v))) rays_C_.push_back(camera.unproject(Vec2(u, v)));
}

int VerifiedCoverage::look(const Pose& T_W_C, Sight* sight) {
  // Mark into a local grid around the camera first (a ray crosses a column many times).
  const double cell = config_.cell_m;
  const int side = 2 * int(std::ceil(range_m_ / cell)) + 3;
  const Vec3 o = T_W_C.translation();
  const int64_t i0 = int64_t(std::floor(o.x() / cell + 0.5)) - side / 2;
  const int64_t j0 = int64_t(std::floor(o.y() / cell + 0.5)) - side / 2;
  std::vector<char> local(size_t(side) * size_t(side), 0);
  for (const Vec3& b : rays_C_) markRay(o, T_W_C.linear() * b, local, i0, j0, side, sight);
  int added = 0;
  for (int a = 0; a < side; ++a)
    for (int b = 0; b < side; ++b)
      if (local[size_t(b) * size_t(side) + size_t(a)]) {
        added += seen_.insert({i0 + a, j0 + b}).second;
        if (sight) sight->columns.push_back({i0 + a, j0 + b});
      }
  return added;
}

void VerifiedCoverage::markRay(const Vec3& o, const Vec3& d, std::vector<char>& local, int64_t i0, int64_t j0, int side,
                               Sight* sight) const {
  // The ray until its first hit (or the clip range), cut to the flight heights.
  const auto hit = truth_.raycastIndexed(o, d, range_m_);
  double t0 = 0.0, t1 = hit ? hit->distance_m : range_m_;
  if (std::abs(d.z()) < 1e-12) {
    if (o.z() < config_.z_lo_m || o.z() > config_.z_hi_m) return;
  } else {
    double a = (config_.z_lo_m - o.z()) / d.z(), b = (config_.z_hi_m - o.z()) / d.z();
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  if (t0 > t1) return;
  if (sight) sight->stretches.emplace_back(o + t0 * d, o + t1 * d);
  // Walk the columns its footprint crosses (cells centred on the nodes).
  const double cell = config_.cell_m;
  const Vec2 p0 = (o + t0 * d).head<2>(), dxy = d.head<2>();
  int64_t c[2] = {int64_t(std::floor(p0.x() / cell + 0.5)), int64_t(std::floor(p0.y() / cell + 0.5))};
  int step[2];
  double t_next[2], t_delta[2];
  for (int k = 0; k < 2; ++k) {
    step[k] = dxy[k] > 0 ? 1 : -1;
    const double edge = (double(c[k]) + (dxy[k] > 0 ? 0.5 : -0.5)) * cell;
    t_delta[k] = std::abs(dxy[k]) < 1e-12 ? 1e300 : cell / std::abs(dxy[k]);
    t_next[k] = std::abs(dxy[k]) < 1e-12 ? 1e300 : t0 + (edge - p0[k]) / dxy[k];
  }
  while (true) {
    const int64_t a = c[0] - i0, b = c[1] - j0;
    if (a < 0 || b < 0 || a >= side || b >= side) return;
    local[size_t(b) * size_t(side) + size_t(a)] = 1;
    const int k = t_next[0] < t_next[1] ? 0 : 1;
    if (t_next[k] > t1) return;
    c[k] += step[k];
    t_next[k] += t_delta[k];
  }
}

bool VerifiedCoverage::partIsFree(const PlacedElement& e, const ColumnIndex& c) const {
  // Quick answer: every point of the element lies within its reach of the centre.
  const double reach = e.footprint == FreeSpaceElement::Footprint::kDisk ? e.radius : e.radius * std::sqrt(3.0);
  const double tol = config_.free_tolerance_m;
  const double d_centre = truth_.distance(e.centre, reach + 1.0);
  // Samples: a lattice over the column's cell and the flight heights, plus the node at the
  // element's height (so that a thin element over the node has a sample).
  const double cell = config_.cell_m, s = config_.lattice_m;
  const Vec2 node(cell * double(c.first), cell * double(c.second));
  const int n_xy = std::max(1, int(std::floor(cell / s)));
  const double off = -0.5 * double(n_xy - 1) * s;
  std::vector<Vec3> samples;
  samples.push_back(Vec3(node.x(), node.y(), std::clamp(e.centre.z(), config_.z_lo_m, config_.z_hi_m)));
  for (double z = config_.z_lo_m + 0.5 * s; z < config_.z_hi_m; z += s)
    for (int a = 0; a < n_xy; ++a)
      for (int b = 0; b < n_xy; ++b) samples.push_back(Vec3(node.x() + off + a * s, node.y() + off + b * s, z));
  bool any = false;
  for (const Vec3& p : samples) {
    if (!elementContains(e, p)) continue;
    any = true;
    if (d_centre - reach >= -tol) continue;  // the whole element is free enough
    if (truth_.distance(p, tol + 1.0) < -tol) return false;
  }
  return any;
}

int VerifiedCoverage::mark(const std::vector<PlacedElement>& elements) {
  const size_t before = verified_.count();
  for (const PlacedElement& e : elements) markElement(e);
  return int(verified_.count() - before);
}

bool VerifiedCoverage::markElement(const PlacedElement& e) {
  bool settled = true;  // false: a covered column not yet seen, look again at the next sample
  for (const ColumnIndex& c : columnsUnder(e, config_.cell_m)) {
    if (verified_.columns().count(c)) continue;
    if (!seen_.count(c)) {
      settled = false;
      continue;
    }
    const auto key = std::make_tuple(e.key, c.first, c.second);
    if (not_free_.count(key)) continue;
    if (partIsFree(e, c))
      verified_.markColumn(c);
    else
      not_free_.insert(key);
  }
  return settled;
}

}  // namespace msb
