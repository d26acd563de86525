// The coverage record of a mission (docs/architecture.md §10) over time: explored columns in the VIO frame
// (the paper's A), inside the exploration box (also as a share of the box's explorable
// columns), and with every free-space element mapped to the true frame by the estimate → truth
// correction of the moment it was first seen (how much of A is real, given drift).
#pragma once

#include <cstdint>
#include <set>
#include <unordered_map>
#include <vector>

#include "core/common/aabb.h"
#include "core/eval/column_coverage.h"
#include "core/eval/coverage_sample.h"
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

  /// The estimate → truth correction at the latest perception frame (T_true_est).
  void setTrueFromEstimate(const Pose& T_true_est) { T_true_est_ = T_true_est; }
  /// Explored columns in the VIO frame; the mission marks the method's free space here
  /// (ColumnCoverage::markFreeSpace) before sample().
  ColumnCoverage& columns() { return columns_; }
  const ColumnCoverage& columns() const { return columns_; }
  /// Explored columns with free space mapped to the true frame.
  const ColumnCoverage& trueFrameColumns() const { return columns_gt_; }
  /// Records a sample at t_s: maps the current free-space elements to the true frame (each
  /// with the correction of the first time its id was seen) and appends A.
  /// Squares are taken as their inscribed disks there: the correction rotates them, and a disk
  /// stays a disk.
  void sample(double t_s, double distance_m, const std::vector<FreeSpaceElement>& free_space);
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

 private:
  Aabb box_;
  std::set<ColumnIndex> box_explorable_;
  ColumnCoverage columns_, columns_gt_;
  // Estimate → truth correction per free-space element id (looked up only, never iterated).
  std::unordered_map<uint64_t, Pose> first_seen_;
  Pose T_true_est_ = Pose::Identity();
  std::vector<CoverageSample> samples_;
};

}  // namespace msb
