#include "core/eval/mission_coverage.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/common/rng.h"

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
MissionCoverage::MissionCoverage(MissionCoverage&&) noexcept = default;
MissionCoverage& MissionCoverage::operator=(MissionCoverage&&) noexcept = default;
MissionCoverage::~MissionCoverage() = default;

void MissionCoverage::enableVerification(const WorldTruth& truth, const FisheyeCamera& camera,
                                         const VerifiedCoverageConfig& config) {
  verified_ = std::make_unique<VerifiedCoverage>(truth, camera, config);
  Aabb heights = box_;
  heights.min.z() = config.z_lo_m, heights.max.z() = config.z_hi_m;
  EarnedScoreConfig e;
  e.cell_m = config.cell_m, e.lattice_m = config.lattice_m, e.free_tolerance_m = config.free_tolerance_m;
  earned_ = std::make_unique<EarnedScore>(truth, heights, e);
}

void MissionCoverage::look(const Pose& T_W_C_true) {
  if (!verified_) return;
  VerifiedCoverage::Sight sight;
  verified_->look(T_W_C_true, &sight);
  camera_inside_ = earned_->inside(T_W_C_true.translation());
  earned_->see(T_W_C_true.translation(), sight);
}

size_t MissionCoverage::verifiedExplorableColumns() const {
  size_t n = 0;
  if (verified_)
    for (const ColumnIndex& c : verified_->verified().columns()) n += box_explorable_.count(c);
  return n;
}

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

void MissionCoverage::enablePublishedOctomapRule(double resolution_m) {
  if (!(resolution_m > 0)) throw std::invalid_argument("MissionCoverage: the OctoMap resolution must be positive");
  published_rule_.emplace(columns_.cellM());
  published_rule_resolution_m_ = resolution_m;
}

double MissionCoverage::publishedRuleRadius(double half_side_m) const {
  // EVAL: sidelen = OCTOMAP_CELLSIZE (0.5) · (len(markers) − index), index = the cell's tree
  // depth, len(markers) = tree depth + 1: 0.5 · (k + 1) for a cell 2^k leaves wide, passed to
  // mark_sphere_explored as a radius.
  const double k = std::max(0.0, std::round(std::log2(2.0 * half_side_m / published_rule_resolution_m_)));
  return 0.5 * (k + 1.0);
}

void MissionCoverage::sample(double t_s, double distance_m, const std::vector<FreeSpaceElement>& free_space) {
  // True-frame columns: each element keeps the correction of the moment it was first seen; an
  // element is placed (and its columns marked) when new or changed, and verified until settled.
  for (const auto& d : free_space) {
    auto [it, fresh] = elements_.try_emplace(d.id);
    ElementState& st = it->second;
    if (fresh) st.T_true_est = T_true_est_;
    if (fresh || st.centre != d.centre || st.radius != d.radius || st.footprint != d.footprint) {
      st.centre = d.centre, st.radius = d.radius, st.footprint = d.footprint;
      PlacedElement& e = st.placed;
      e.centre = st.T_true_est * d.centre;
      e.radius = d.radius;
      e.footprint = d.footprint;
      e.yaw_rad = yawOf(st.T_true_est.linear());
      const double key[6] = {double(d.id), e.centre.x(), e.centre.y(), e.centre.z(), e.radius, e.yaw_rad};
      e.key = fnv1a64(key, sizeof(key), uint64_t(d.footprint));
      columns_gt_.markPlaced(e);
      if (published_rule_ && d.footprint == FreeSpaceElement::Footprint::kSquare)
        published_rule_->markDisk(d.centre.head<2>(), publishedRuleRadius(d.radius));
      st.settled = false;
      if (earned_) earned_->declare(e);
    }
    if (verified_ && !st.settled) st.settled = verified_->markElement(st.placed);
  }
  const double cell = columns_.cellM();
  CoverageSample c;
  c.t_s = t_s;
  c.area_m2 = columns_.areaM2();
  c.area_box_m2 = double(columns_.countInside(box_.min.head<2>(), box_.max.head<2>())) * cell * cell;
  c.area_gt_m2 = columns_gt_.areaM2();
  if (verified_) c.area_verified_m2 = verified_->verified().areaM2();
  if (earned_) c.score_earned_m3 = earned_->tally().earnedM3();
  if (!camera_inside_) time_outside_s_ += t_s - last_sample_t_s_;
  last_sample_t_s_ = t_s;
  c.distance_m = distance_m;
  if (!box_explorable_.empty()) c.box_share = double(exploredExplorableColumns()) / double(box_explorable_.size());
  samples_.push_back(c);
}

}  // namespace msb
