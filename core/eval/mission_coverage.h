// The coverage record of a mission (docs/architecture.md §10) over time: explored columns in the VIO frame
// (the paper's A), inside the exploration box (also as a share of the box's explorable
// columns), and with every free-space element mapped to the true frame by the estimate → truth
// correction of the moment it was first seen (how much of A is real, given drift).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/common/aabb.h"
#include "core/eval/column_coverage.h"
#include "core/eval/coverage_sample.h"
#include "core/eval/earned_score.h"
#include "core/eval/verified_coverage.h"
#include "core/explorer/snapshot.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Explorable columns of `box` in the metric's node convention: the nodes (cell·i, cell·j)
/// inside the box whose cell of side `cell_m` is not fully occupied.
std::set<ColumnIndex> boxExplorableNodes(const WorldTruth& truth, const Aabb& box, double cell_m);

/// Cumulative coverage of one mission.
class MissionCoverage {
 public:
  /// `box`: the exploration box; `box_explorable`: its explorable nodes (empty = unknown).
  MissionCoverage(const Aabb& box, std::set<ColumnIndex> box_explorable);
  MissionCoverage(MissionCoverage&&) noexcept;
  MissionCoverage& operator=(MissionCoverage&&) noexcept;
  ~MissionCoverage();

  /// The estimate → truth correction at the latest perception frame (T_true_est).
  void setTrueFromEstimate(const Pose& T_true_est) { T_true_est_ = T_true_est; }
  /// Explored columns in the VIO frame; the mission marks the method's free space here
  /// (ColumnCoverage::markFreeSpace) before sample().
  ColumnCoverage& columns() { return columns_; }
  const ColumnCoverage& columns() const { return columns_; }
  /// Explored columns with free space mapped to the true frame.
  const ColumnCoverage& trueFrameColumns() const { return columns_gt_; }
  /// Turns on the verified coverage and the earned score (worlds with ground truth; the camera
  /// gives the rays).
  void enableVerification(const WorldTruth& truth, const FisheyeCamera& camera, const VerifiedCoverageConfig& config);
  /// Also scores OctoMap free cells (square elements of leaf size `resolution_m` · 2^k) by the
  /// authors' evaluation rule (EVAL process_explored_volume_octomap_gridmarking, BUG-11): a
  /// cell of depth index k from the leaves counts as a disk of radius 0.5·(k + 1) m about its
  /// centre (the marker array's side-length formula used as a radius), VIO frame, unbounded.
  void enablePublishedOctomapRule(double resolution_m);
  /// The columns of the published rule (null unless enabled).
  const ColumnCoverage* publishedRuleColumns() const { return published_rule_ ? &*published_rule_ : nullptr; }
  /// The camera's true pose at this sample (verified coverage: what the camera saw).
  void look(const Pose& T_W_C_true);
  /// Records a sample at t_s: places the current free-space elements in the true frame (each
  /// with the correction of the first time its id was seen: disks moved, squares moved and
  /// turned by the correction's yaw), verifies them, and appends A.
  void sample(double t_s, double distance_m, const std::vector<FreeSpaceElement>& free_space);
  /// The verified coverage (null unless enabled).
  const VerifiedCoverage* verified() const { return verified_.get(); }
  /// The earned score (null unless verification is enabled).
  EarnedScore* earned() { return earned_.get(); }
  /// Seconds of metric samples whose camera was outside the box (beyond the earned score's margin).
  double timeOutsideBoxS() const { return time_outside_s_; }
  /// Verified columns that are explorable columns of the box.
  size_t verifiedExplorableColumns() const;
  /// All samples so far.
  const std::vector<CoverageSample>& samples() const { return samples_; }
  /// The exploration box and its explorable nodes.
  const Aabb& box() const { return box_; }
  int boxExplorableColumns() const { return int(box_explorable_.size()); }
  /// Explored columns (VIO frame) that are explorable columns of the box: box_share's numerator.
  size_t exploredExplorableColumns() const;
  /// True-frame explored columns that are explorable columns of the box: what share of the
  /// real box the mission has seen, with each free-space element placed where it truly was.
  size_t trueFrameExploredExplorableColumns() const;

  /// The disk radius the authors' evaluation rule gives a free OctoMap cell of half side
  /// `half_side_m` (0.5·(k + 1) for a cell 2^k leaves wide; enablePublishedOctomapRule first).
  double publishedRuleRadius(double half_side_m) const;

 private:
  Aabb box_;
  std::set<ColumnIndex> box_explorable_;
  ColumnCoverage columns_, columns_gt_;
  std::optional<ColumnCoverage> published_rule_;
  double published_rule_resolution_m_ = 0.0;
  // What the metric knows of each free-space element id (looked up only, never iterated): the
  // estimate → truth correction of its first sight, its geometry as last seen, its placement in
  // the true frame, and whether verification has nothing left to decide for it. An element seen
  // again unchanged costs one lookup.
  struct ElementState {
    Pose T_true_est = Pose::Identity();
    Vec3 centre = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    double radius = -1.0;
    FreeSpaceElement::Footprint footprint = FreeSpaceElement::Footprint::kDisk;
    PlacedElement placed;
    bool settled = false;
  };
  std::unordered_map<uint64_t, ElementState> elements_;
  Pose T_true_est_ = Pose::Identity();
  std::vector<CoverageSample> samples_;
  std::unique_ptr<VerifiedCoverage> verified_;
  std::unique_ptr<EarnedScore> earned_;
  bool camera_inside_ = true;  // at the latest look
  double time_outside_s_ = 0.0, last_sample_t_s_ = 0.0;
};

}  // namespace msb
