// Determinism hashes of a run (docs/architecture.md, "Determinism"): FNV-1a over the final map and
// the coverage record (the trajectory's hash is the loop's: tools/engine/records.h). Same scenario + seed + build on
// the same machine ⇒ the same hashes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/eval/column_coverage.h"
#include "core/eval/coverage_sample.h"
#include "core/explorer/snapshot.h"

namespace msb {

/// Hash of a map snapshot (free space, obstacles, frontiers).
uint64_t hashSnapshot(const ExplorerSnapshot& snap);

/// The mission's determinism hash: trajectory, final map, explored columns and coverage samples.
uint64_t hashMission(uint64_t trajectory_hash, uint64_t map_hash, const ColumnCoverage& columns,
                     const std::vector<CoverageSample>& coverage);

}  // namespace msb
