// A uniform hash grid of ids at 3D positions, for radius and box queries. Queries return ids
// sorted ascending, so results never depend on hash-table iteration order. Each cell keeps the
// positions with the ids, so distance tests need no lookup in the owner's containers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// Hash grid over ids with positions.
class PointGrid {
 public:
  /// `cell_m`: grid cell size.
  explicit PointGrid(double cell_m) : cell_(cell_m) {}
  /// Adds an id at a position.
  void insert(uint64_t id, const Vec3& p);
  /// Removes an id previously inserted at p.
  void erase(uint64_t id, const Vec3& p);
  /// Ids whose cells intersect the axis-aligned box [lo, hi] (a superset of those inside).
  std::vector<uint64_t> inBox(const Vec3& lo, const Vec3& hi) const;
  /// Ids whose cells intersect the cube around p of half-size r (superset of the ball).
  std::vector<uint64_t> near(const Vec3& p, double r) const { return inBox(p.array() - r, p.array() + r); }
  /// True if `pred(id, position)` holds for some id whose cell intersects the cube around p of
  /// half-size r. Unordered, allocation-free: for existence tests only (results never depend
  /// on order).
  template <class Pred>
  bool anyNear(const Vec3& p, double r, Pred pred) const {
    CellRange c;
    if (!cellsOf(p.array() - r, p.array() + r, &c)) return false;
    for (int64_t x = c.lo[0]; x <= c.hi[0]; ++x)
      for (int64_t y = c.lo[1]; y <= c.hi[1]; ++y)
        for (int64_t z = c.lo[2]; z <= c.hi[2]; ++z) {
          const auto it = cells_.find(key(x, y, z));
          if (it == cells_.end()) continue;
          for (const Entry& e : it->second)
            if (pred(e.id, e.position)) return true;
        }
    return false;
  }
  /// Ids (ascending) for which `pred(id, position)` holds, among those whose cells intersect
  /// the cube around p of half-size r.
  template <class Pred>
  std::vector<uint64_t> select(const Vec3& p, double r, Pred pred) const {
    std::vector<uint64_t> out;
    visitBox(p.array() - r, p.array() + r, [&](const Entry& e) {
      if (pred(e.id, e.position)) out.push_back(e.id);
    });
    std::sort(out.begin(), out.end());
    return out;
  }
  /// Calls `f(id, position)` for every id whose cell intersects the cube around p of half-size
  /// r, in no particular order: for uses whose result does not depend on the order (counts).
  template <class F>
  void forEachNear(const Vec3& p, double r, F f) const {
    visitBox(p.array() - r, p.array() + r, [&](const Entry& e) { f(e.id, e.position); });
  }
  /// Number of ids.
  size_t size() const { return size_; }

 private:
  struct Entry {
    uint64_t id;
    Vec3 position;
  };
  // An inclusive range of cells per axis.
  struct CellRange {
    int64_t lo[3], hi[3];
  };
  // The cells of [lo, hi] that can hold entries: cut to the range of cells ever occupied (no
  // cell outside it has entries, so queries find the same). False if none.
  bool cellsOf(const Vec3& lo, const Vec3& hi, CellRange* c) const {
    for (int k = 0; k < 3; ++k) {
      c->lo[k] = std::max(cellOf(lo[k]), occupied_.lo[k]);
      c->hi[k] = std::min(cellOf(hi[k]), occupied_.hi[k]);
      if (c->lo[k] > c->hi[k]) return false;
    }
    return true;
  }
  // Calls f(entry) for every entry whose cell intersects [lo, hi] (in no particular order).
  template <class F>
  void visitBox(const Vec3& lo, const Vec3& hi, F f) const {
    CellRange c;
    if (!cellsOf(lo, hi, &c)) return;
    const int64_t x0 = c.lo[0], x1 = c.hi[0], y0 = c.lo[1], y1 = c.hi[1], z0 = c.lo[2], z1 = c.hi[2];
    const long cells = (x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1);
    if (cells > long(cells_.size()) * 4) {
      // Large box: scan the occupied cells instead of the box's cells.
      for (const auto& [k, entries] : cells_) {
        const int64_t x = int64_t(k & kAxisMask) - kAxisOffset, y = int64_t((k >> 21) & kAxisMask) - kAxisOffset;
        const int64_t z = int64_t((k >> 42) & kAxisMask) - kAxisOffset;
        if (x >= x0 && x <= x1 && y >= y0 && y <= y1 && z >= z0 && z <= z1)
          for (const Entry& e : entries) f(e);
      }
      return;
    }
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t z = z0; z <= z1; ++z) {
          const auto it = cells_.find(key(x, y, z));
          if (it != cells_.end())
            for (const Entry& e : it->second) f(e);
        }
  }
  static constexpr uint64_t kAxisMask = (1ULL << 21) - 1;  // 21 bits per axis (±1M cells)
  static constexpr int64_t kAxisOffset = 1 << 20;
  static uint64_t key(int64_t x, int64_t y, int64_t z);
  int64_t cellOf(double v) const { return int64_t(std::floor(v / cell_)); }
  double cell_;
  std::unordered_map<uint64_t, std::vector<Entry>> cells_;
  size_t size_ = 0;
  // Every cell ever given an entry lies in this range (empty until the first insert).
  CellRange occupied_{{INT64_MAX, INT64_MAX, INT64_MAX}, {INT64_MIN, INT64_MIN, INT64_MIN}};
};

}  // namespace msb
