// Determinism hashes of a run (docs/architecture.md §3): FNV-1a over the trajectory rows, the final map and
// the coverage record. Same scenario + seed + build on the same machine ⇒ the same hashes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/eval/column_coverage.h"
#include "core/eval/map_snapshot.h"
#include "core/eval/coverage_sample.h"

namespace msb {

/// One row of trajectory.csv: ground truth, the VIO estimate and the reference.
struct TrajectoryRow {
  double t_s;
  Vec3 position_m;       ///< ground truth
  Quat orientation;      ///< ground truth
  Vec3 velocity_mps;     ///< ground truth
  Vec3 est_position_m;   ///< VIO estimate
  double est_yaw_rad;    ///< VIO estimate
  Vec3 ref_position_m;   ///< trajectory reference (estimate frame)
  double ref_yaw_rad;
};

/// Hash of trajectory rows (time, estimate, true pose and velocity).
uint64_t hashTrajectory(const std::vector<TrajectoryRow>& rows);

/// Hash of a map snapshot (free space, obstacles, frontiers).
uint64_t hashSnapshot(const ExplorerSnapshot& snap);

/// The mission's determinism hash: trajectory, final map, explored columns and coverage samples.
uint64_t hashMission(uint64_t trajectory_hash, uint64_t map_hash, const ColumnCoverage& columns,
                     const std::vector<CoverageSample>& coverage);

}  // namespace msb
