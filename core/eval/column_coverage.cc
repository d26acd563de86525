#include "core/eval/column_coverage.h"

#include <cmath>
#include <stdexcept>

namespace msb {

ColumnCoverage::ColumnCoverage(double cell_m) : cell_(cell_m) {
  if (!(cell_m > 0)) throw std::invalid_argument("ColumnCoverage: cell size must be positive");
}

int ColumnCoverage::markDisk(const Vec2& c, double r) {
  if (!(r >= 0)) return 0;
  int added = 0;
  // Nodes with |x − cx| ≤ r: i in [ceil((cx − r)/cell), floor((cx + r)/cell)].
  const int64_t i0 = int64_t(std::ceil((c.x() - r) / cell_)), i1 = int64_t(std::floor((c.x() + r) / cell_));
  for (int64_t i = i0; i <= i1; ++i) {
    const double dx = cell_ * double(i) - c.x();
    const double h2 = r * r - dx * dx;
    if (h2 < 0) continue;
    const double h = std::sqrt(h2);
    const int64_t j0 = int64_t(std::ceil((c.y() - h) / cell_)), j1 = int64_t(std::floor((c.y() + h) / cell_));
    for (int64_t j = j0; j <= j1; ++j) {
      const double dy = cell_ * double(j) - c.y();
      if (dx * dx + dy * dy > r * r) continue;  // guard the rounding of sqrt at the boundary
      added += columns_.insert({i, j}).second;
    }
  }
  return added;
}

int ColumnCoverage::markSquare(const Vec2& c, double half) {
  if (!(half >= 0)) return 0;
  int added = 0;
  const int64_t i0 = int64_t(std::ceil((c.x() - half) / cell_)), i1 = int64_t(std::floor((c.x() + half) / cell_));
  const int64_t j0 = int64_t(std::ceil((c.y() - half) / cell_)), j1 = int64_t(std::floor((c.y() + half) / cell_));
  for (int64_t i = i0; i <= i1; ++i)
    for (int64_t j = j0; j <= j1; ++j) added += columns_.insert({i, j}).second;
  return added;
}

size_t ColumnCoverage::countInside(const Vec2& lo, const Vec2& hi) const {
  size_t n = 0;
  for (const auto& c : columns_) {
    const Vec2 p = node(c);
    n += p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
  }
  return n;
}

int ColumnCoverage::markPlaced(const PlacedElement& e) {
  if (e.footprint == FreeSpaceElement::Footprint::kDisk) return markDisk(e.centre.head<2>(), e.radius);
  int added = 0;
  for (const ColumnIndex& c : columnsUnder(e, cell_)) added += columns_.insert(c).second;
  return added;
}

std::vector<ColumnIndex> columnsUnder(const PlacedElement& e, double cell) {
  std::vector<ColumnIndex> out;
  if (!(e.radius >= 0)) return out;
  if (e.footprint == FreeSpaceElement::Footprint::kDisk) {
    ColumnCoverage disk(cell);
    disk.markDisk(e.centre.head<2>(), e.radius);
    return {disk.columns().begin(), disk.columns().end()};
  }
  // A turned square: the nodes of its bounding box whose offset, turned back, lies inside it.
  const double reach = e.radius * std::sqrt(2.0), c = std::cos(e.yaw_rad), s = std::sin(e.yaw_rad);
  const Vec2 m = e.centre.head<2>();
  const int64_t i0 = int64_t(std::ceil((m.x() - reach) / cell)), i1 = int64_t(std::floor((m.x() + reach) / cell));
  const int64_t j0 = int64_t(std::ceil((m.y() - reach) / cell)), j1 = int64_t(std::floor((m.y() + reach) / cell));
  for (int64_t i = i0; i <= i1; ++i)
    for (int64_t j = j0; j <= j1; ++j) {
      const double dx = cell * double(i) - m.x(), dy = cell * double(j) - m.y();
      if (std::abs(c * dx + s * dy) <= e.radius && std::abs(-s * dx + c * dy) <= e.radius) out.push_back({i, j});
    }
  return out;
}

int ColumnCoverage::markFreeSpace(const std::vector<FreeSpaceElement>& elements) {
  int added = 0;
  for (const FreeSpaceElement& e : elements)
    added += e.footprint == FreeSpaceElement::Footprint::kSquare ? markSquare(e.centre.head<2>(), e.radius)
                                                                 : markDisk(e.centre.head<2>(), e.radius);
  return added;
}

}  // namespace msb
