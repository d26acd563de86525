#include "core/map/point_grid.h"

#include <algorithm>
#include <cmath>

namespace msb {

uint64_t PointGrid::key(int64_t x, int64_t y, int64_t z) {
  // 21 bits per axis (±1M cells), packed.
  const uint64_t m = (1ULL << 21) - 1;
  return (uint64_t(x + (1 << 20)) & m) | ((uint64_t(y + (1 << 20)) & m) << 21) |
         ((uint64_t(z + (1 << 20)) & m) << 42);
}

void PointGrid::insert(uint64_t id, const Vec3& p) {
  cells_[key(int64_t(std::floor(p.x() / cell_)), int64_t(std::floor(p.y() / cell_)),
             int64_t(std::floor(p.z() / cell_)))]
      .push_back(id);
  ++size_;
}

void PointGrid::erase(uint64_t id, const Vec3& p) {
  const auto it = cells_.find(key(int64_t(std::floor(p.x() / cell_)), int64_t(std::floor(p.y() / cell_)),
                                  int64_t(std::floor(p.z() / cell_))));
  if (it == cells_.end()) return;
  auto& v = it->second;
  const auto pos = std::find(v.begin(), v.end(), id);
  if (pos == v.end()) return;
  v.erase(pos);
  --size_;
  if (v.empty()) cells_.erase(it);
}

std::vector<uint64_t> PointGrid::inBox(const Vec3& lo, const Vec3& hi) const {
  std::vector<uint64_t> out;
  const int64_t x0 = int64_t(std::floor(lo.x() / cell_)), x1 = int64_t(std::floor(hi.x() / cell_));
  const int64_t y0 = int64_t(std::floor(lo.y() / cell_)), y1 = int64_t(std::floor(hi.y() / cell_));
  const int64_t z0 = int64_t(std::floor(lo.z() / cell_)), z1 = int64_t(std::floor(hi.z() / cell_));
  const long cells = (x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1);
  if (cells > long(cells_.size()) * 4) {
    // Large box: scan the occupied cells instead of the box's cells.
    for (const auto& [k, ids] : cells_) {
      const int64_t x = int64_t(k & ((1ULL << 21) - 1)) - (1 << 20);
      const int64_t y = int64_t((k >> 21) & ((1ULL << 21) - 1)) - (1 << 20);
      const int64_t z = int64_t((k >> 42) & ((1ULL << 21) - 1)) - (1 << 20);
      if (x >= x0 && x <= x1 && y >= y0 && y <= y1 && z >= z0 && z <= z1) out.insert(out.end(), ids.begin(), ids.end());
    }
  } else {
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t z = z0; z <= z1; ++z) {
          const auto it = cells_.find(key(x, y, z));
          if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
        }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace msb
