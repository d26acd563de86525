// The earned score (docs/metrics.md, "The earned score"): what a method's free space is worth to a
// leaderboard, in m³ of the exploration box. Each column whose node lies in the box is cut into a
// lattice of samples (`lattice_m` apart, the column's 2.5 m cell by the box's heights). A sample
// is *declared* once an element of the method's free space, placed in the true frame, contains it
// (cumulative, like A). At any moment
//   credited      = declared samples that are truly free (outside every obstacle) and that a
//                   camera ray crossed within `credit_range_m` of the camera, from a pose
//                   inside the box (within `inside_margin_m`);
//   falsely free  = declared samples more than `free_tolerance_m` inside an obstacle;
//   unseen        = declared samples that are not falsely free, in columns no ray from inside
//                   the box has crossed (at any range);
//   earned        = (credited − falsely free − unseen) · lattice³.
// Declaring nothing earns 0; a claim the method cannot back by sight or by truth costs what it
// would have bought. Volume, not columns: a thin element buys only the samples it holds.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "core/common/aabb.h"
#include "core/eval/column_coverage.h"
#include "core/eval/verified_coverage.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Parameters of the earned score (defaults: docs/metrics.md).
struct EarnedScoreConfig {
  double cell_m = 2.5;            ///< column size (the paper's)
  double lattice_m = 0.5;         ///< sample spacing (each sample stands for lattice³ of volume)
  double free_tolerance_m = 0.5;  ///< deeper than this inside an obstacle: falsely free
  double inside_margin_m = 1.0;   ///< a camera this far outside the box still sees from inside
  double credit_range_m = 10.0;   ///< a sample is credited when a ray crossed it this close to the camera
};

/// The earned score's parts, in m³.
struct EarnedTally {
  double credited_m3 = 0, falsely_free_m3 = 0, unseen_m3 = 0;
  /// credited − falsely free − unseen.
  double earnedM3() const { return credited_m3 - falsely_free_m3 - unseen_m3; }
};

/// The earned score of one mission (box columns only; the lattice's truth is read once per column).
class EarnedScore {
 public:
  EarnedScore(const WorldTruth& truth, const Aabb& box, const EarnedScoreConfig& config = {});

  /// Whether a camera at `p` sees from inside the box (the box grown by the margin).
  bool inside(const Vec3& p) const;
  /// What the camera at `camera_position` saw (VerifiedCoverage::look): its columns count as
  /// seen from inside, and the samples its rays crossed within the credit range as seen, only
  /// when the camera is inside. The rays are followed in steps of half the lattice.
  void see(const Vec3& camera_position, const VerifiedCoverage::Sight& sight);
  /// Adds the samples the element contains (in box columns) to the declared volume.
  void declare(const PlacedElement& e);
  /// The score now.
  EarnedTally tally() const;
  /// The truly free volume of the box's columns (the most `credited_m3` can reach).
  double boxFreeM3();
  /// Samples per column.
  int samplesPerColumn() const { return n_xy_ * n_xy_ * n_z_; }

 private:
  struct ColumnState {
    std::vector<uint64_t> declared, free, deep, seen;  // one bit per sample
    bool truth_read = false, seen_inside = false;
  };
  bool inBox(const ColumnIndex& c) const;
  Vec3 samplePoint(const ColumnIndex& c, int k) const;
  ColumnState& bits(const ColumnIndex& c);          // creates it (no truth read yet)
  ColumnState& state(const ColumnIndex& c);         // creates it, reading its truth on first use
  void seeAlong(const Vec3& from, const Vec3& to);  // marks the samples a stretch crosses

  const WorldTruth& truth_;
  Aabb box_;
  EarnedScoreConfig config_;
  int n_xy_ = 0, n_z_ = 0;
  std::map<ColumnIndex, ColumnState> columns_;  // box columns touched so far (ordered)
};

}  // namespace msb
