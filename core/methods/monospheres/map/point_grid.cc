#include "core/methods/monospheres/map/point_grid.h"

#include <algorithm>
#include <cmath>

namespace msb {

uint64_t PointGrid::key(int64_t x, int64_t y, int64_t z) {
  return (uint64_t(x + kAxisOffset) & kAxisMask) | ((uint64_t(y + kAxisOffset) & kAxisMask) << 21) |
         ((uint64_t(z + kAxisOffset) & kAxisMask) << 42);
}

void PointGrid::insert(uint64_t id, const Vec3& p) {
  const int64_t c[3] = {cellOf(p.x()), cellOf(p.y()), cellOf(p.z())};
  cells_[key(c[0], c[1], c[2])].push_back({id, p});
  ++size_;
  for (int k = 0; k < 3; ++k)
    occupied_.lo[k] = std::min(occupied_.lo[k], c[k]), occupied_.hi[k] = std::max(occupied_.hi[k], c[k]);
}

void PointGrid::erase(uint64_t id, const Vec3& p) {
  const auto it = cells_.find(key(cellOf(p.x()), cellOf(p.y()), cellOf(p.z())));
  if (it == cells_.end()) return;
  auto& v = it->second;
  const auto pos = std::find_if(v.begin(), v.end(), [id](const Entry& e) { return e.id == id; });
  if (pos == v.end()) return;
  v.erase(pos);
  --size_;
  if (v.empty()) cells_.erase(it);
}

std::vector<uint64_t> PointGrid::inBox(const Vec3& lo, const Vec3& hi) const {
  std::vector<uint64_t> out;
  visitBox(lo, hi, [&](const Entry& e) { out.push_back(e.id); });
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace msb
