// One sample of a mission's coverage record (a row of coverage.csv).
#pragma once

namespace msb {

/// Explored area at one moment of a mission.
struct CoverageSample {
  double t_s = 0;
  double area_m2 = 0;          ///< unbounded, VIO frame (as the paper)
  double area_box_m2 = 0;      ///< columns whose node lies in the exploration box
  double area_gt_m2 = 0;       ///< unbounded, free space mapped to the true frame when first seen
  double distance_m = 0;       ///< flown so far (ground truth)
};

}  // namespace msb
