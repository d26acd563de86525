// A uniform hash grid of ids at 3D positions, for radius and box queries. Queries return ids
// sorted ascending, so results never depend on hash-table iteration order.
#pragma once

#include <cmath>
#include <cstdint>
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
  /// True if `pred(id)` holds for some id whose cell intersects the cube around p of half-size
  /// r. Unordered, allocation-free: for existence tests only (results never depend on order).
  template <class Pred>
  bool anyNear(const Vec3& p, double r, Pred pred) const {
    const Vec3 lo = p.array() - r, hi = p.array() + r;
    for (int64_t x = cellOf(lo.x()); x <= cellOf(hi.x()); ++x)
      for (int64_t y = cellOf(lo.y()); y <= cellOf(hi.y()); ++y)
        for (int64_t z = cellOf(lo.z()); z <= cellOf(hi.z()); ++z) {
          const auto it = cells_.find(key(x, y, z));
          if (it == cells_.end()) continue;
          for (uint64_t id : it->second)
            if (pred(id)) return true;
        }
    return false;
  }
  /// Number of ids.
  size_t size() const { return size_; }

 private:
  static uint64_t key(int64_t x, int64_t y, int64_t z);
  int64_t cellOf(double v) const { return int64_t(std::floor(v / cell_)); }
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint64_t>> cells_;
  size_t size_ = 0;
};

}  // namespace msb
