#include "core/eval/earned_score.h"

#include <bit>
#include <cmath>
#include <stdexcept>

namespace msb {

namespace {
size_t popcount(const std::vector<uint64_t>& a) {
  size_t n = 0;
  for (uint64_t w : a) n += size_t(std::popcount(w));
  return n;
}
bool bit(const std::vector<uint64_t>& a, int k) { return (a[size_t(k) / 64] >> (k % 64)) & 1u; }
void setBit(std::vector<uint64_t>& a, int k) { a[size_t(k) / 64] |= uint64_t(1) << (k % 64); }
}  // namespace

EarnedScore::EarnedScore(const WorldTruth& truth, const Aabb& box, const EarnedScoreConfig& config)
    : truth_(truth), box_(box), config_(config) {
  if (!(config.cell_m > 0) || !(config.lattice_m > 0) || !(config.free_tolerance_m >= 0) ||
      !(config.inside_margin_m >= 0))
    throw std::invalid_argument("EarnedScore: cell, lattice, tolerance and margin must be positive");
  if (!(box.max.z() > box.min.z())) throw std::invalid_argument("EarnedScore: empty flight heights");
  n_xy_ = std::max(1, int(std::floor(config.cell_m / config.lattice_m + 1e-9)));
  n_z_ = std::max(1, int(std::floor((box.max.z() - box.min.z()) / config.lattice_m + 1e-9)));
}

bool EarnedScore::inside(const Vec3& p) const {
  const double m = config_.inside_margin_m;
  return (p.array() >= box_.min.array() - m).all() && (p.array() <= box_.max.array() + m).all();
}

bool EarnedScore::inBox(const ColumnIndex& c) const {
  const double x = config_.cell_m * double(c.first), y = config_.cell_m * double(c.second);
  return x >= box_.min.x() && x <= box_.max.x() && y >= box_.min.y() && y <= box_.max.y();
}

Vec3 EarnedScore::samplePoint(const ColumnIndex& c, int k) const {
  // k = (z · n_xy + b) · n_xy + a: a lattice centred on the node, from lattice/2 above the floor.
  const double s = config_.lattice_m, off = -0.5 * double(n_xy_ - 1) * s;
  const int a = k % n_xy_, b = (k / n_xy_) % n_xy_, z = k / (n_xy_ * n_xy_);
  return Vec3(config_.cell_m * double(c.first) + off + a * s, config_.cell_m * double(c.second) + off + b * s,
              box_.min.z() + (z + 0.5) * s);
}

EarnedScore::ColumnState& EarnedScore::bits(const ColumnIndex& c) {
  ColumnState& st = columns_[c];
  if (st.seen.empty()) {
    const size_t words = size_t(samplesPerColumn() + 63) / 64;
    st.declared.assign(words, 0), st.free.assign(words, 0), st.deep.assign(words, 0), st.seen.assign(words, 0);
  }
  return st;
}

EarnedScore::ColumnState& EarnedScore::state(const ColumnIndex& c) {
  ColumnState& st = bits(c);
  if (st.truth_read) return st;
  // The column's truth, once: free (outside every obstacle) and deep (past the tolerance).
  const int n = samplesPerColumn();
  const double tol = config_.free_tolerance_m;
  for (int k = 0; k < n; ++k) {
    const double d = truth_.distance(samplePoint(c, k), tol + 1.0);
    if (d >= 0) setBit(st.free, k);
    if (d < -tol) setBit(st.deep, k);
  }
  st.truth_read = true;
  return st;
}

void EarnedScore::see(const Vec3& camera_position, const VerifiedCoverage::Sight& sight) {
  if (!inside(camera_position)) return;
  for (const ColumnIndex& c : sight.columns)
    if (inBox(c)) columns_[c].seen_inside = true;
  // Each ray's stretch, cut to the credit range about the camera.
  const double range = config_.credit_range_m;
  for (const auto& [from, to] : sight.stretches) {
    const Vec3 d = to - from;
    const double len = d.norm(), start = (from - camera_position).norm();
    if (start >= range || len <= 0) continue;
    seeAlong(from, from + d * (std::min(len, range - start) / len));
  }
}

void EarnedScore::seeAlong(const Vec3& from, const Vec3& to) {
  // Sample indices: x = s·gx on the lattice (the nodes are multiples of it), z from the floor.
  const double s = config_.lattice_m, cell = config_.cell_m;
  const int half = n_xy_ / 2;
  const int steps = int(std::ceil((to - from).norm() / (0.5 * s)));
  ColumnIndex last{INT64_MIN, INT64_MIN};
  ColumnState* st = nullptr;
  for (int k = 0; k <= steps; ++k) {
    const Vec3 p = from + (to - from) * (steps ? double(k) / steps : 0.0);
    const ColumnIndex c{int64_t(std::floor(p.x() / cell + 0.5)), int64_t(std::floor(p.y() / cell + 0.5))};
    if (c != last) {
      last = c;
      st = inBox(c) ? &bits(c) : nullptr;
    }
    if (!st) continue;
    const int a = int(std::lround((p.x() - cell * double(c.first)) / s)) + half;
    const int b = int(std::lround((p.y() - cell * double(c.second)) / s)) + half;
    const int z = int(std::floor((p.z() - box_.min.z()) / s));
    if (a < 0 || b < 0 || a >= n_xy_ || b >= n_xy_ || z < 0 || z >= n_z_) continue;
    setBit(st->seen, (z * n_xy_ + b) * n_xy_ + a);
  }
}

void EarnedScore::declare(const PlacedElement& e) {
  // The box columns whose cell meets the element's xy bounds (a turned square reaches r·√2).
  const double reach = e.footprint == FreeSpaceElement::Footprint::kDisk ? e.radius : e.radius * std::sqrt(2.0);
  if (e.centre.z() - reach > box_.max.z() || e.centre.z() + reach < box_.min.z()) return;
  const double cell = config_.cell_m;
  const double x0 = std::max(e.centre.x() - reach, box_.min.x() - cell);
  const double x1 = std::min(e.centre.x() + reach, box_.max.x() + cell);
  const double y0 = std::max(e.centre.y() - reach, box_.min.y() - cell);
  const double y1 = std::min(e.centre.y() + reach, box_.max.y() + cell);
  if (x0 > x1 || y0 > y1) return;
  const int n = samplesPerColumn();
  for (int64_t i = int64_t(std::floor(x0 / cell + 0.5)); i <= int64_t(std::floor(x1 / cell + 0.5)); ++i)
    for (int64_t j = int64_t(std::floor(y0 / cell + 0.5)); j <= int64_t(std::floor(y1 / cell + 0.5)); ++j) {
      const ColumnIndex c{i, j};
      if (!inBox(c)) continue;
      ColumnState& st = state(c);
      for (int k = 0; k < n; ++k)
        if (!bit(st.declared, k) && elementContains(e, samplePoint(c, k))) setBit(st.declared, k);
    }
}

EarnedTally EarnedScore::tally() const {
  size_t credited = 0, falsely = 0, unseen = 0;
  for (const auto& [c, st] : columns_) {
    if (!st.truth_read) continue;  // seen, nothing declared
    for (size_t w = 0; w < st.declared.size(); ++w) {
      const uint64_t d = st.declared[w];
      falsely += size_t(std::popcount(d & st.deep[w]));
      credited += size_t(std::popcount(d & st.free[w] & st.seen[w]));
      if (!st.seen_inside) unseen += size_t(std::popcount(d & ~st.deep[w]));
    }
  }
  const double v = std::pow(config_.lattice_m, 3);
  return {double(credited) * v, double(falsely) * v, double(unseen) * v};
}

double EarnedScore::boxFreeM3() {
  const double cell = config_.cell_m;
  size_t n = 0;
  for (int64_t i = int64_t(std::ceil(box_.min.x() / cell)); double(i) * cell <= box_.max.x(); ++i)
    for (int64_t j = int64_t(std::ceil(box_.min.y() / cell)); double(j) * cell <= box_.max.y(); ++j)
      n += popcount(state({i, j}).free);
  return double(n) * std::pow(config_.lattice_m, 3);
}

}  // namespace msb
