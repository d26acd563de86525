// Verified coverage (docs/metrics.md, "Verified coverage"): the paper's column metric with each
// column earned, not claimed. A 2.5 m column (i, j) is verified once, at some metric sample,
//   (a) a free-space element, placed in the true frame as the true-frame coverage places it,
//       covers its node (c·i, c·j) — a disk, or a square turned by the correction's yaw;
//   (b) the part of that element inside the column between the flight heights is truly free:
//       no sample of it (a 0.5 m lattice) lies more than `free_tolerance_m` inside an obstacle of
//       the world's truth geometry; and
//   (c) the column has been seen: at that sample or an earlier one, a camera ray from the true
//       camera pose passed through the column between the flight heights inside the field of
//       view, within the clip range, before it hit any truth geometry.
// Cumulative, like A. The flight heights are the exploration box's vertical range; the rays are
// the camera's pixels on a grid of `ray_spacing_px` (full-resolution pixels).
#pragma once

#include <cstdint>
#include <set>
#include <tuple>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/eval/column_coverage.h"
#include "core/explorer/snapshot.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Parameters of the verified coverage (defaults: docs/metrics.md).
struct VerifiedCoverageConfig {
  double cell_m = 2.5;              ///< column size (the paper's)
  double z_lo_m = 0.0, z_hi_m = 0;  ///< flight heights: the exploration box's vertical range
  double lattice_m = 0.5;           ///< sample spacing of an element's part in a column
  double free_tolerance_m = 0.5;    ///< how deep a sample may lie inside an obstacle and still count free
  double ray_spacing_px = 8.0;      ///< the camera rays: every this many full-resolution pixels
};

/// True if the point lies in the element's solid (a ball, or a cube turned by yaw_rad).
bool elementContains(const PlacedElement& e, const Vec3& p);

/// Cumulative verified columns of one mission.
class VerifiedCoverage {
 public:
  VerifiedCoverage(const WorldTruth& truth, const FisheyeCamera& camera, const VerifiedCoverageConfig& config);

  /// What one look saw: every column marked, and each ray's free stretch (from `from` to `to`:
  /// the camera to its first hit or the clip range, cut to the flight heights).
  struct Sight {
    std::vector<ColumnIndex> columns;
    std::vector<std::pair<Vec3, Vec3>> stretches;
  };
  /// Marks the columns the camera sees from the true camera pose T_W_C (and tells what it saw
  /// in `sight`, when given). Returns how many were new.
  int look(const Pose& T_W_C, Sight* sight = nullptr);
  /// Verifies the columns the elements cover (conditions a–c). Returns how many were new.
  int mark(const std::vector<PlacedElement>& elements);
  /// Verifies the columns one element covers; returns true when nothing is left to decide for it
  /// (each column it covers is verified or not free for it), false while one is not yet seen.
  bool markElement(const PlacedElement& e);
  /// Marks a column as seen (for tests of mark() without a camera).
  void markSeenForTest(const ColumnIndex& c) { seen_.insert(c); }

  /// Columns seen so far.
  const std::set<ColumnIndex>& seen() const { return seen_; }
  /// Verified columns.
  const ColumnCoverage& verified() const { return verified_; }
  /// Whether the part of `e` in column `c` between the flight heights is truly free (b); false
  /// when the element has no part there.
  bool partIsFree(const PlacedElement& e, const ColumnIndex& c) const;

 private:
  void markRay(const Vec3& o, const Vec3& d, std::vector<char>& local, int64_t i0, int64_t j0, int side,
               Sight* sight) const;

  const WorldTruth& truth_;
  VerifiedCoverageConfig config_;
  double range_m_;            // the camera's clip range
  std::vector<Vec3> rays_C_;  // unit bearings of the sampled pixels (camera frame)
  std::set<ColumnIndex> seen_;
  ColumnCoverage verified_;
  std::set<std::tuple<uint64_t, int64_t, int64_t>> not_free_;  // (element key, column) pairs that failed (b)
};

}  // namespace msb
