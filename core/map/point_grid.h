// A uniform hash grid of ids at 3D positions, for radius and box queries. Queries return ids
// sorted ascending, so results never depend on hash-table iteration order.
#pragma once

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
  /// Number of ids.
  size_t size() const { return size_; }

 private:
  static uint64_t key(int64_t x, int64_t y, int64_t z);
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint64_t>> cells_;
  size_t size_ = 0;
};

}  // namespace msb
