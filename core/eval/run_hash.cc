#include "core/eval/run_hash.h"

#include "core/common/rng.h"

namespace msb {

uint64_t hashSnapshot(const ExplorerSnapshot& snap) {
  uint64_t h = fnv1a64(nullptr, 0);
  for (const auto& d : snap.free_space) {
    const double v[5] = {double(d.id), d.centre.x(), d.centre.y(), d.centre.z(), d.radius};
    h = fnv1a64(v, sizeof(v), h);
  }
  for (const auto& p : snap.obstacles) h = fnv1a64(p.data(), 3 * sizeof(double), h);
  for (const auto& p : snap.frontiers) h = fnv1a64(p.data(), 3 * sizeof(double), h);
  return h;
}

uint64_t hashMission(uint64_t trajectory_hash, uint64_t map_hash, const ColumnCoverage& columns,
                     const std::vector<CoverageSample>& coverage) {
  uint64_t h = fnv1a64(&trajectory_hash, sizeof(uint64_t));
  h = fnv1a64(&map_hash, sizeof(uint64_t), h);
  for (const auto& c : columns.columns()) h = fnv1a64(&c, sizeof(c), h);
  for (const auto& c : coverage) {
    const double v[4] = {c.t_s, c.area_m2, c.area_box_m2, c.area_gt_m2};
    h = fnv1a64(v, sizeof(v), h);
  }
  return h;
}

}  // namespace msb
