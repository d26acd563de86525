#include "core/eval/mission_coverage.h"

#include <cmath>

namespace msb {

std::set<ColumnIndex> boxExplorableNodes(const WorldTruth& truth, const Aabb& box, double cell) {
  // Align the box to the cells centred on the nodes (cell·i, cell·j) that lie inside it.
  Aabb aligned = box;
  int64_t first[2];
  for (int k = 0; k < 2; ++k) {
    first[k] = int64_t(std::ceil(box.min[k] / cell));
    aligned.min[k] = (double(first[k]) - 0.5) * cell;
    aligned.max[k] = (std::floor(box.max[k] / cell) + 0.5) * cell;
  }
  std::set<ColumnIndex> nodes;
  if ((aligned.max.head<2>().array() <= aligned.min.head<2>().array()).any()) return nodes;
  for (const Column& c : truth.explorableColumns(aligned, cell)) nodes.insert({first[0] + c.ix, first[1] + c.iy});
  return nodes;
}

MissionCoverage::MissionCoverage(const Aabb& box, std::set<ColumnIndex> box_explorable)
    : box_(box), box_explorable_(std::move(box_explorable)) {}

size_t MissionCoverage::exploredExplorableColumns() const {
  size_t n = 0;
  for (const ColumnIndex& c : columns_.columns()) n += box_explorable_.count(c);
  return n;
}

size_t MissionCoverage::trueFrameExploredExplorableColumns() const {
  size_t n = 0;
  for (const ColumnIndex& c : columns_gt_.columns()) n += box_explorable_.count(c);
  return n;
}

void MissionCoverage::sample(double t_s, double distance_m, const std::vector<FreeSpaceElement>& free_space) {
  // True-frame columns: each element keeps the correction of the moment it was first seen.
  for (const auto& d : free_space) {
    const Pose& T = first_seen_.emplace(d.id, T_true_est_).first->second;
    columns_gt_.markDisk((T * d.centre).head<2>(), d.radius);
  }
  const double cell = columns_.cellM();
  CoverageSample c;
  c.t_s = t_s;
  c.area_m2 = columns_.areaM2();
  c.area_box_m2 = double(columns_.countInside(box_.min.head<2>(), box_.max.head<2>())) * cell * cell;
  c.area_gt_m2 = columns_gt_.areaM2();
  c.distance_m = distance_m;
  if (!box_explorable_.empty()) c.box_share = double(exploredExplorableColumns()) / double(box_explorable_.size());
  samples_.push_back(c);
}

}  // namespace msb
